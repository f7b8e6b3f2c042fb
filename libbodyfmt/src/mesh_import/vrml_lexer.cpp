#include "mesh_import/vrml_lexer.h"

namespace bodyfmt::mesh {

namespace {

bool is_separator(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ',' || c == '\f' || c == '\v';
}

bool ends_word(char c) {
  return is_separator(c) || c == '{' || c == '}' || c == '[' || c == ']' || c == '#' || c == '"';
}

}  // namespace

void VrmlLexer::advance(std::size_t n) {
  for (std::size_t i = 0; i < n && pos_ < text_.size(); ++i, ++pos_) {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
  }
}

const Token& VrmlLexer::peek() {
  if (!has_lookahead_) {
    lookahead_ = scan();
    has_lookahead_ = true;
  }
  return lookahead_;
}

Token VrmlLexer::next() {
  if (has_lookahead_) {
    has_lookahead_ = false;
    return lookahead_;
  }
  return scan();
}

Token VrmlLexer::scan() {
  // Skip separators and comments.
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (is_separator(c)) {
      advance(1);
    } else if (c == '#') {
      while (pos_ < text_.size() && text_[pos_] != '\n') advance(1);
    } else {
      break;
    }
  }
  Token token;
  token.line = line_;
  token.column = column_;
  if (pos_ >= text_.size()) return token;  // kEnd

  const char c = text_[pos_];
  const auto single = [&](TokenKind kind) {
    token.kind = kind;
    token.text = text_.substr(pos_, 1);
    advance(1);
    return token;
  };
  switch (c) {
    case '{': return single(TokenKind::kOpenBrace);
    case '}': return single(TokenKind::kCloseBrace);
    case '[': return single(TokenKind::kOpenBracket);
    case ']': return single(TokenKind::kCloseBracket);
    default: break;
  }
  if (c == '"') {
    const std::size_t start = pos_ + 1;
    std::size_t end = start;
    while (end < text_.size() && text_[end] != '"') end += (text_[end] == '\\') ? 2 : 1;
    if (end >= text_.size()) {
      token.kind = TokenKind::kError;
      token.text = "unterminated string";
      pos_ = text_.size();
      return token;
    }
    token.kind = TokenKind::kString;
    token.text = text_.substr(start, end - start);
    advance(end + 1 - pos_);
    return token;
  }
  std::size_t end = pos_;
  while (end < text_.size() && !ends_word(text_[end])) ++end;
  token.text = text_.substr(pos_, end - pos_);
  const char first = token.text.front();
  token.kind = (first == '+' || first == '-' || first == '.' || (first >= '0' && first <= '9'))
                   ? TokenKind::kNumber
                   : TokenKind::kIdentifier;
  advance(end - pos_);
  return token;
}

std::string unescape_string(std::string_view raw) {
  std::string out;
  out.reserve(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] == '\\' && i + 1 < raw.size()) ++i;
    out += raw[i];
  }
  return out;
}

}  // namespace bodyfmt::mesh
