#pragma once
/// VRML97 tokenizer (ISO/IEC 14772-1 §5.1): whitespace and commas separate tokens, `#` starts
/// a comment to the end of the line, `{ } [ ]` are tokens of their own, strings are
/// double-quoted with backslash escapes. The optional `#VRML V2.0 utf8` header is just a
/// comment here, which is how files without it (the PA10 parts) are accepted.

#include <string>
#include <string_view>

namespace bodyfmt::mesh {

enum class TokenKind {
  kEnd,
  kIdentifier,
  kNumber,
  kString,
  kOpenBrace,
  kCloseBrace,
  kOpenBracket,
  kCloseBracket,
  kError
};

struct Token {
  TokenKind kind = TokenKind::kEnd;
  std::string_view text;  ///< raw text; for strings, without the quotes (escapes kept)
  int line = 1;
  int column = 1;
};

class VrmlLexer {
 public:
  explicit VrmlLexer(std::string_view text) : text_(text) {}

  /// The next token without consuming it.
  const Token& peek();
  Token next();

 private:
  Token scan();
  void advance(std::size_t n);

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
  Token lookahead_;
  bool has_lookahead_ = false;
};

/// Decodes the escapes (`\"`, `\\`) of a string token.
std::string unescape_string(std::string_view raw);

}  // namespace bodyfmt::mesh
