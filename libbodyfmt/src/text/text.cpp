#include <bodyfmt/text.h>

#include <cstddef>

#include <fmt/format.h>

namespace bodyfmt::text {

namespace {

/// utf8_sequence's length, also 0 for the characters XML 1.0 does not allow (U+FFFE, U+FFFF; the Char
/// production of XML 1.0 §2.2). Control characters are checked by the callers.
std::size_t xml_char_length(std::string_view text, std::size_t i) {
  unsigned code_point = 0;
  const std::size_t n = utf8_sequence(text, i, code_point);
  return code_point == 0xFFFE || code_point == 0xFFFF ? 0 : n;
}

bool allowed_control(char c) { return c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

std::size_t utf8_sequence(std::string_view s, std::size_t i, unsigned& code_point) {
  const auto c = static_cast<unsigned char>(s[i]);
  code_point = c;
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned min = 0;
  if ((c & 0xE0) == 0xC0)
    n = 2, min = 0x80, code_point = c & 0x1Fu;
  else if ((c & 0xF0) == 0xE0)
    n = 3, min = 0x800, code_point = c & 0x0Fu;
  else if ((c & 0xF8) == 0xF0)
    n = 4, min = 0x10000, code_point = c & 0x07u;
  else
    return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const auto cc = static_cast<unsigned char>(s[i + k]);
    if ((cc & 0xC0) != 0x80) return 0;
    code_point = (code_point << 6) | (cc & 0x3Fu);
  }
  if (code_point < min || code_point > 0x10FFFF || (code_point >= 0xD800 && code_point <= 0xDFFF)) return 0;
  return n;
}

bool is_utf8(std::string_view s) {
  unsigned code_point = 0;
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8_sequence(s, i, code_point);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string json_quote(std::string_view s) {
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(s.size() + 2);
  out += '"';
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char ch = s[i];
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c >= 0x80) {
      unsigned code_point = 0;
      const std::size_t n = utf8_sequence(s, i, code_point);
      if (n == 0) {
        out += "\\ufffd";  // invalid UTF-8 byte: the replacement character
      } else {
        out.append(s.substr(i, n));
        i += n - 1;
      }
      continue;
    }
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          out += "\\u00";
          out += kHex[c >> 4];
          out += kHex[c & 0xF];
        } else {
          out += ch;
        }
    }
  }
  out += '"';
  return out;
}

std::string uri_path_encode(std::string_view path) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char ch : path) {
    const auto c = static_cast<unsigned char>(ch);
    const bool unreserved = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                            c == '.' || c == '_' || c == '~' || c == '/';
    if (unreserved) {
      out += ch;
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 0xF];
    }
  }
  return out;
}

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

bool is_xml_text(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 && !allowed_control(text[i])) return false;
    const std::size_t n = xml_char_length(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string xml_comment_text(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = xml_char_length(text, i);
    if (n == 0 || (c < 0x20 && !allowed_control(text[i]))) {
      out += '?';
      ++i;
      continue;
    }
    if (text[i] == '-' && !out.empty() && out.back() == '-') out += ' ';
    out.append(text.substr(i, n));
    i += n;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

namespace {

// YAML 1.2's printable set (§5.1) less the byte order mark, which a parser drops: tab, LF, CR,
// x20-x7E, x85, xA0-xD7FF, xE000-xFFFD without xFEFF, x10000 up.
bool yaml_printable(unsigned c) {
  return c == '\t' || c == '\n' || c == '\r' || (c >= 0x20 && c <= 0x7e) || c == 0x85 || (c >= 0xa0 && c <= 0xd7ff) ||
         (c >= 0xe000 && c <= 0xfffd && c != 0xfeff) || c >= 0x10000;
}

}  // namespace

std::string yaml_escape(std::string_view s, bool escape_quotes) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    unsigned c = 0;
    const std::size_t n = utf8_sequence(s, i, c);
    if (n == 0) {
      out += "\\ufffd";
      ++i;
      continue;
    }
    if (escape_quotes && (c == '"' || c == '\\')) {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c == '\n' || c == '\t' || c == '\r') {
      out += c == '\n' ? "\\n" : c == '\t' ? "\\t" : "\\r";
    } else if (c == 0x85 || c == 0x2028 || c == 0x2029) {
      out += c == 0x85 ? "\\N" : c == 0x2028 ? "\\L" : "\\P";  // line breaks a parser would fold
    } else if (!yaml_printable(c)) {
      out += c <= 0xff ? fmt::format("\\x{:02x}", c) : fmt::format("\\u{:04x}", c);
    } else {
      out.append(s.substr(i, n));
    }
    i += n;
  }
  return out;
}

std::string yaml_quote(std::string_view s) { return "\"" + yaml_escape(s, true) + "\""; }

}  // namespace bodyfmt::text
