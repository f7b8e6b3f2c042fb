#include <bodyfmt/converters/names.h>

namespace bodyfmt::converters {

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

namespace {

// Length of the UTF-8 sequence starting at text[i], or 0 when it is malformed (truncated,
// overlong, a surrogate, above U+10FFFF) or is a character XML 1.0 does not allow
// (U+FFFE, U+FFFF; the Char production of XML 1.0 §2.2). Control characters are checked by
// the callers.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  if (n == 1) return 1;
  unsigned cp = n == 2 ? (c & 0x1Fu) : n == 3 ? (c & 0x0Fu) : (c & 0x07u);
  for (std::size_t k = 1; k < n; ++k) {
    const auto cc = static_cast<unsigned char>(text[i + k]);
    if ((cc & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (cc & 0x3Fu);
  }
  static constexpr unsigned kMin[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < kMin[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF) || cp == 0xFFFE || cp == 0xFFFF) return 0;
  return n;
}

bool allowed_control(char c) { return c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

bool is_xml_text(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 && !allowed_control(text[i])) return false;
    const std::size_t n = utf8_length(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string xml_comment_text(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8_length(text, i);
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

std::string urdf_name_problem(std::string_view name) {
  if (name.empty()) return "it is empty";
  if (!is_xml_text(name)) return "it contains characters XML cannot hold";
  auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!letter(name.front())) return "it does not start with a letter or '_'";
  for (char c : name) {
    if (!letter(c) && !digit(c) && c != '-' && c != '.') {
      return "it contains characters other than letters, digits, '_', '-' and '.'";
    }
  }
  return {};
}

std::string file_stem(std::string_view name) {
  std::string out;
  for (char c : name) {
    const bool ok =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    out += ok ? c : '_';
  }
  if (out.empty() || out.front() == '.') out.insert(out.begin(), '_');
  return out;
}

}  // namespace bodyfmt::converters
