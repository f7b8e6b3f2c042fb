// bodyls's conversions: UTF-16 positions and byte offsets of a text (surrogate pairs, invalid
// UTF-8, every line break), the features' 1-based byte points, file URIs, and the framing.
#include "feature_requests.h"
#include "framing.h"
#include "message_json.h"
#include "text_positions.h"
#include "uri.h"

#include <doctest/doctest.h>

#include <cctype>
#include <string>
#include <string_view>

using bodyfmt::lsp::MessageReader;
using bodyfmt::lsp::TextLines;
using bodyfmt::lsp::Utf16Position;

namespace {

// "a", U+1F600 (4 bytes, 2 units), "b" CR LF, U+00F6 (2 bytes) CR, "x" LF, "" (an empty last line).
const std::string kText =
    "a\xF0\x9F\x98\x80"
    "b\r\n\xC3\xB6\rx\n";

}  // namespace

TEST_CASE("lsp text lines: UTF-16 positions of bytes and back, with a surrogate pair and every line break") {
  const TextLines lines(kText);
  CHECK(lines.line_count() == 4);
  CHECK(lines.line(0) ==
        "a\xF0\x9F\x98\x80"
        "b");
  CHECK(lines.line(1) == "\xC3\xB6");
  CHECK(lines.line(2) == "x");
  CHECK(lines.line(3).empty());
  CHECK(lines.position_of(5) == Utf16Position{0, 3});  // "b" after a and the pair
  CHECK(lines.offset_of({0, 3}) == 5);
  CHECK(lines.offset_of({0, 2}) == 1);                 // inside the pair: before it
  CHECK(lines.position_of(3) == Utf16Position{0, 1});  // inside the pair's bytes: its start
  CHECK(lines.offset_of({1, 1}) == 10);                // after U+00F6
  CHECK(lines.offset_of({1, 99}) == 10);               // past the line's end: its end
  CHECK(lines.offset_of({2, 1}) == 12);
  CHECK(lines.offset_of({9, 0}) == kText.size());  // past the last line: the end
  CHECK(lines.position_of(kText.size()) == Utf16Position{3, 0});
  CHECK(lines.position_of(7) == Utf16Position{0, 4});  // between CR and LF: the line's end
}

TEST_CASE("lsp text lines: an invalid UTF-8 byte is one unit, and positions stay inside the text") {
  const std::string text = "\xFF\xC0\x80z\xE2\x82";  // invalid lead, overlong NUL, a cut sequence
  const TextLines lines(text);
  CHECK(lines.position_of(3) == Utf16Position{0, 3});
  CHECK(lines.offset_of({0, 4}) == 4);
  CHECK(lines.position_of(text.size()) == Utf16Position{0, 6});
  CHECK(lines.offset_of({0, 100}) == text.size());
}

TEST_CASE("lsp text lines: the token at a finding's 1-based byte column") {
  const std::string text = "  mass: 27.0 # kg\n  name: \"\xF0\x9F\x98\x80 x\", b: 1\n";
  const TextLines lines(text);
  auto range = lines.token_range(1, 3);  // the key
  CHECK(range.start == Utf16Position{0, 2});
  CHECK(range.end == Utf16Position{0, 6});
  range = lines.token_range(1, 9);  // the value, not its comment
  CHECK(range.start == Utf16Position{0, 8});
  CHECK(range.end == Utf16Position{0, 12});
  range = lines.token_range(2, 9);  // a quoted string with a surrogate pair
  CHECK(range.start == Utf16Position{1, 8});
  CHECK(range.end == Utf16Position{1, 14});
  range = lines.token_range(9, 1);  // past the end: inside the text
  CHECK(range.start.line == 2);
}

TEST_CASE("lsp incremental changes apply in UTF-16 positions") {
  std::string text = kText;
  bodyfmt::lsp::apply_change(text, {{0, 1}, {0, 3}}, "Z");  // replace the pair
  CHECK(text == "aZb\r\n\xC3\xB6\rx\n");
  bodyfmt::lsp::apply_change(text, {{1, 0}, {0, 3}}, "");  // start after end: the same range
  CHECK(text == "aZb\xC3\xB6\rx\n");
  bodyfmt::lsp::apply_change(text, {{5, 0}, {6, 0}}, "tail");  // past the end: appended
  CHECK(text == "aZb\xC3\xB6\rx\ntail");
}

TEST_CASE("lsp features' points: the protocol's positions as 1-based lines and byte columns") {
  const TextLines lines(kText);
  auto point = bodyfmt::lsp::text_point_of(lines, {0, 3});
  CHECK(point.line == 1);
  CHECK(point.column == 6);
  point = bodyfmt::lsp::text_point_of(lines, {7, 0});  // past the last line: its end
  CHECK(point.line == 4);
  CHECK(point.column == 1);
  const auto range = bodyfmt::lsp::utf16_range_of(lines, {{1, 2}, {2, 3}});
  CHECK(range.start == Utf16Position{0, 1});
  CHECK(range.end == Utf16Position{1, 1});
}

TEST_CASE("lsp file URIs") {
  CHECK(bodyfmt::lsp::path_from_uri("file:///a%20b/c%C3%B6.body") == std::optional<std::string>("/a b/c\xC3\xB6.body"));
  CHECK(bodyfmt::lsp::path_from_uri("file://localhost/x.body") == std::optional<std::string>("/x.body"));
  CHECK_FALSE(bodyfmt::lsp::path_from_uri("untitled:Untitled-1"));
  CHECK_FALSE(bodyfmt::lsp::path_from_uri("file://server/share/x.body"));
  CHECK_FALSE(bodyfmt::lsp::path_from_uri("file:///a%00b"));
  CHECK(bodyfmt::lsp::uri_from_path("/a b/c\xC3\xB6#.body") == "file:///a%20b/c%C3%B6%23.body");
  // Every byte but NUL in a file name comes back through the server's own decoder, and the URI
  // holds only unreserved characters, '/' and %XX (the encoding bodyls shares with SARIF).
  for (int byte = 1; byte < 256; ++byte) {
    const std::string path =
        std::string("/d/a") + static_cast<char>(byte) + "41z.body";  // "%41" unencoded reads back as "A"
    const std::string uri = bodyfmt::lsp::uri_from_path(path);
    CAPTURE(byte);
    CHECK(bodyfmt::lsp::path_from_uri(uri) == std::optional<std::string>(path));
    for (std::size_t i = std::string("file://").size(); i < uri.size(); ++i) {
      const char c = uri[i];
      const bool allowed =
          std::isalnum(static_cast<unsigned char>(c)) || std::string_view("-._~/%").find(c) != std::string_view::npos;
      CHECK(allowed);
    }
  }
  CHECK(bodyfmt::lsp::path_from_uri(bodyfmt::lsp::uri_from_path("/x y/%z.body")) ==
        std::optional<std::string>("/x y/%z.body"));
}

TEST_CASE("lsp framing: messages split anywhere, bad headers resynchronised, huge bodies skipped") {
  MessageReader reader(100);
  const std::string stream = "Content-Length: 2\r\n\r\n{}Content-Length: 3\r\nContent-Type: x\r\n\r\n[1]";
  std::string body, error;
  for (const char c : stream) reader.feed(&c, 1);  // a byte at a time
  CHECK(reader.next(body, error) == MessageReader::Status::kMessage);
  CHECK(body == "{}");
  CHECK(reader.next(body, error) == MessageReader::Status::kMessage);
  CHECK(body == "[1]");
  CHECK(reader.next(body, error) == MessageReader::Status::kNeedMore);

  const std::string bad = "Content-Length: x\r\n\r\n{}Content-Length: 1\r\n\r\n1";
  reader.feed(bad.data(), bad.size());
  CHECK(reader.next(body, error) == MessageReader::Status::kBadFrame);
  CHECK(reader.next(body, error) == MessageReader::Status::kMessage);
  CHECK(body == "1");

  const std::string huge = "Content-Length: 1000\r\n\r\n" + std::string(1000, 'x') + "Content-Length: 1\r\n\r\n2";
  reader.feed(huge.data(), 30);
  CHECK(reader.next(body, error) == MessageReader::Status::kBadFrame);
  reader.feed(huge.data() + 30, huge.size() - 30);
  CHECK(reader.next(body, error) == MessageReader::Status::kMessage);
  CHECK(body == "2");
}

TEST_CASE("lsp framing: two different Content-Length headers refuse the frame, the next one is read") {
  for (const std::string lengths : {"2\r\ncontent-length: 9", "9\r\nContent-Length: 2", "1\r\nContent-Length: 2"}) {
    MessageReader reader(100);
    const std::string stream = "Content-Length: " + lengths + "\r\n\r\n{}Content-Length: 3\r\n\r\n[1]";
    reader.feed(stream.data(), stream.size());
    std::string body, error;
    CHECK(reader.next(body, error) == MessageReader::Status::kBadFrame);
    CHECK(reader.next(body, error) == MessageReader::Status::kMessage);
    CHECK(body == "[1]");
  }
  MessageReader reader(100);
  const std::string same = "Content-Length: 2\r\nContent-Length: 2\r\n\r\n{}";
  reader.feed(same.data(), same.size());
  std::string body, error;
  CHECK(reader.next(body, error) == MessageReader::Status::kMessage);
  CHECK(body == "{}");
}

TEST_CASE("lsp message depth: arrays and objects are counted outside strings, escapes included") {
  using bodyfmt::lsp::nests_deeper_than;
  CHECK_FALSE(nests_deeper_than("[[[]]]", 3));
  CHECK(nests_deeper_than("[[[[]]]]", 3));
  CHECK(nests_deeper_than("[{\"a\":[{}]}]", 3));
  CHECK_FALSE(nests_deeper_than("[][][][]", 1));        // siblings are not nested
  CHECK_FALSE(nests_deeper_than("[\"[[[[{{\"]", 1));    // brackets in a string
  CHECK_FALSE(nests_deeper_than("[\"\\\"[[[[\"]", 1));  // an escaped quote does not end the string
  CHECK(nests_deeper_than("[\"\\\\\"[[]]]", 2));        // an escaped backslash does not escape the quote
  CHECK_FALSE(nests_deeper_than("]]]][[", 2));          // stray closers make no room
  CHECK(nests_deeper_than(std::string(100000, '[') + std::string(100000, ']'), 256));
}
