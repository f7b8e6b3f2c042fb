// JSON and XML quoting through the public header (bodyfmt/text.h), one copy for the reports and
// the writers. The two differ on purpose in what they do with a non-character (U+FFFE): JSON
// can carry it, XML 1.0 cannot.
#include <bodyfmt/text.h>
#include <doctest/doctest.h>

using namespace bodyfmt;

TEST_CASE("text: JSON quoting escapes what JSON needs and replaces invalid UTF-8") {
  CHECK(text::json_quote("") == "\"\"");
  CHECK(text::json_quote("a\"b\\c\b\f\n\r\t\x7f\x1f") == "\"a\\\"b\\\\c\\b\\f\\n\\r\\t\\u007f\\u001f\"");
  CHECK(text::json_quote(std::string_view("\0x", 2)) == "\"\\u0000x\"");
  CHECK(text::json_quote("\xef\xbf\xbe") == "\"\xef\xbf\xbe\"");                      // U+FFFE is valid UTF-8
  CHECK(text::json_quote("\xed\xa0\x80") == "\"\\ufffd\\ufffd\\ufffd\"");             // a surrogate: three bad bytes
  CHECK(text::json_quote("\xf0\x9f\x98") == "\"\\ufffd\\ufffd\\ufffd\"");             // truncated 4-byte sequence
  CHECK(text::json_quote("\xf4\x90\x80\x80") == "\"\\ufffd\\ufffd\\ufffd\\ufffd\"");  // above U+10FFFF
}

TEST_CASE("text: XML text quoting, the XML 1.0 character test and comment text") {
  CHECK(text::xml_escape("<a href=\"x\">&'</a>") == "&lt;a href=&quot;x&quot;&gt;&amp;&apos;&lt;/a&gt;");
  CHECK(text::xml_escape("caf\xc3\xa9") == "caf\xc3\xa9");
  CHECK(text::is_xml_text(""));
  CHECK(text::is_xml_text("tab\tnew\nreturn\r"));
  CHECK_FALSE(text::is_xml_text(std::string_view("\0", 1)));
  CHECK_FALSE(text::is_xml_text("\xef\xbf\xbe"));  // U+FFFE: not an XML character
  CHECK(text::xml_comment_text("--x-") == "- -x- ");
  CHECK(text::xml_comment_text("a\x01z") == "a?z");
  CHECK(text::xml_comment_text("\xef\xbf\xbe!") == "\?\?\?!");  // each byte of the non-character
  CHECK(text::xml_comment_text("ok \xe2\x80\xa2") == "ok \xe2\x80\xa2");
}
