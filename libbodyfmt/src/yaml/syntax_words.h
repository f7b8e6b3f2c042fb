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
  std::string hint;  ///< empty: libyaml's words are the hint
  /// The edit that makes the line read as meant, when there is one: replace the bytes
  /// [begin, end) of the text with `replacement`.
  struct Edit {
    std::size_t begin = 0;
    std::size_t end = 0;
    std::string replacement;
  };
  std::optional<Edit> edit;
};

/// Explains the error libyaml found at 1-based `line` of `text`, or nullopt when it is neither
/// a tab in an indentation nor a line indented unlike its neighbours (libyaml's words stay).
std::optional<SyntaxWords> syntax_in_words(std::string_view text, int line);

/// Explains libyaml's "mapping values are not allowed in this context" at the colon at 1-based
/// `line` and byte `column` when that colon is inside a plain value (`type: RigidBody:`, `name:
/// a: b`): a value cannot end with ':' or hold ": " unless it is quoted. nullopt for any other
/// colon.
std::optional<SyntaxWords> colon_in_value(std::string_view text, int line, int column);

}  // namespace bodyfmt::yaml
