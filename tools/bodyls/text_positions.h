#pragma once
/// Positions in a document's text: the protocol's 0-based lines and UTF-16 code units, the
/// project's 1-based lines and byte columns, and byte offsets. Any bytes are a valid text:
/// an invalid UTF-8 byte counts as one code unit (as the U+FFFD an editor shows for it), so a
/// position is always inside the text.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::lsp {

/// The protocol's position: 0-based line, 0-based UTF-16 code unit in the line.
struct Utf16Position {
  int line = 0;
  int character = 0;
  friend bool operator==(const Utf16Position& a, const Utf16Position& b) {
    return a.line == b.line && a.character == b.character;
  }
};

struct Utf16Range {
  Utf16Position start;
  Utf16Position end;
};

/// The lines of a text (ended by "\n", "\r\n" or "\r", as the protocol and libyaml count them).
/// Holds a view: the text must outlive it.
class TextLines {
 public:
  explicit TextLines(std::string_view text);

  int line_count() const { return static_cast<int>(starts_.size()); }
  /// Line `line` (0-based) without its line break; empty past the end.
  std::string_view line(int line) const;
  std::size_t line_start(int line) const;

  /// The byte offset of `position`. Past the last line: the end of the text; past a line's
  /// end: that line's end; inside a character (a surrogate pair's second half): its start.
  std::size_t offset_of(Utf16Position position) const;
  /// The position of the byte `offset` (clamped to the text; inside a character: its start).
  Utf16Position position_of(std::size_t offset) const;
  /// The byte offset of a 1-based line and 1-based byte column (0 or past the end: clamped).
  std::size_t offset_of_column(int line, int column) const;

  /// From the 1-based `line` and byte `column` a finding points at to the end of the token
  /// there (a quoted string, a plain scalar or key, up to ": ", ",", "]", "}" or a comment);
  /// an empty token covers one character, if the line has one.
  Utf16Range token_range(int line, int column) const;

 private:
  std::string_view text_;
  std::vector<std::size_t> starts_;
};

/// Bytes of the UTF-8 sequence at `text[i]` (1 for an invalid byte) and its UTF-16 length.
std::size_t utf8_sequence_length(std::string_view text, std::size_t i, int* utf16_units);

/// Applies one change of textDocument/didChange: replaces [start, end) (converted with the text
/// before the change) with `replacement`.
void apply_change(std::string& text, Utf16Range range, std::string_view replacement);

}  // namespace bodyfmt::lsp
