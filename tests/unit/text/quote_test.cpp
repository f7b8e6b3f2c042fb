// JSON and XML quoting through the public header (bodyfmt/text.h), one copy for the reports and
// the writers. The two differ on purpose in what they do with a non-character (U+FFFE): JSON
// can carry it, XML 1.0 cannot.
#include <bodyfmt/text.h>
#include <bodyfmt/yaml.h>
#include <doctest/doctest.h>

#include <optional>
#include <string>
#include <vector>

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

namespace {

std::string utf8(char32_t c) {
  std::string s;
  if (c < 0x80) {
    s += static_cast<char>(c);
  } else if (c < 0x800) {
    s += static_cast<char>(0xc0 | (c >> 6));
    s += static_cast<char>(0x80 | (c & 0x3f));
  } else if (c < 0x10000) {
    s += static_cast<char>(0xe0 | (c >> 12));
    s += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
    s += static_cast<char>(0x80 | (c & 0x3f));
  } else {
    s += static_cast<char>(0xf0 | (c >> 18));
    s += static_cast<char>(0x80 | ((c >> 12) & 0x3f));
    s += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
    s += static_cast<char>(0x80 | (c & 0x3f));
  }
  return s;
}

// What libyaml (the reference: the .body loader and every YAML tool read through it) makes of
// `value: <text>`; nullopt when it refuses the document.
std::optional<std::string> yaml_value(const std::string& text) {
  CollectingSink sink;
  std::optional<YamlDocument> doc = parse_yaml_text(text, "quote.yaml", sink);
  if (!doc || !doc->root().is_mapping()) return std::nullopt;
  std::optional<YamlEntry> value = doc->root().find("value");
  if (!value || !value->value.is_scalar()) return std::nullopt;
  return std::string(value->value.scalar());
}

}  // namespace

TEST_CASE("text: a YAML double-quoted scalar reads back as the text, for every kind of character") {
  std::vector<char32_t> code_points;
  for (char32_t c = 0; c < 0x3000; ++c) code_points.push_back(c);
  for (char32_t c : {0xd7ffu, 0xe000u, 0xfeffu, 0xfffdu, 0xfffeu, 0xffffu, 0x10000u, 0x1f600u, 0x10ffffu})
    code_points.push_back(c);
  for (char32_t c : code_points) {
    const std::string text = "a" + utf8(c) + "\"\\ b";
    const std::string quoted = text::yaml_quote(text);
    CAPTURE(static_cast<unsigned>(c));
    CHECK(yaml_value("value: " + quoted + "\n") == text);
    // In a comment the same text cannot end the line: the key after it is still read.
    CHECK(yaml_value("# " + text::yaml_escape(text, false) + "\nvalue: 1\n") == std::string("1"));
  }
  CHECK(text::yaml_quote("plain") == "\"plain\"");
  CHECK(text::yaml_quote("a\nb\tc") == "\"a\\nb\\tc\"");
  CHECK(text::yaml_quote("\xc2\x85\xe2\x80\xa8") == "\"\\N\\L\"");  // line breaks a parser would fold
  CHECK(text::yaml_quote("\xef\xbb\xbf") == "\"\\ufeff\"");         // a byte order mark would be dropped
  CHECK(text::yaml_quote("\xff") == "\"\\ufffd\"");                 // not UTF-8
}
