#include <bodyfmt/converters/names.h>

namespace bodyfmt::converters {

std::string urdf_name_problem(std::string_view name) {
  if (name.empty()) return "it is empty";
  if (!text::is_xml_text(name)) return "it contains characters XML cannot hold";
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
