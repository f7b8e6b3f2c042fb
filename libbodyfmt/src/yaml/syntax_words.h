#pragma once
// A YAML syntax error in the words of someone editing a .body file by hand: which line is
// indented differently from the lines it belongs with, or where a tab stands in the
// indentation. libyaml's own words (the parser's state) are kept by the caller as a note.

#include <optional>
#include <string>
#include <string_view>

namespace bodyfmt::yaml {

struct SyntaxWords {
  int line = 0;    ///< 1-based
  int column = 0;  ///< 1-based byte column
  std::string message;
};

/// Explains the error libyaml found at 1-based `line` of `text`, or nullopt when it is neither
/// a tab in an indentation nor a line indented unlike its neighbours (libyaml's words stay).
std::optional<SyntaxWords> syntax_in_words(std::string_view text, int line);

}  // namespace bodyfmt::yaml
