#include "xml_positions.h"

#include <tinyxml2.h>

#include <cstring>

namespace bodyfmt::urdf_import {

XmlPositions::XmlPositions(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {
  line_starts_.push_back(0);
  for (std::size_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') line_starts_.push_back(i + 1);
}

std::string_view XmlPositions::line_text(int line) const {
  if (line < 1 || static_cast<std::size_t>(line) > line_starts_.size()) return {};
  const std::size_t begin = line_starts_[static_cast<std::size_t>(line) - 1];
  const std::size_t end = static_cast<std::size_t>(line) < line_starts_.size()
                              ? line_starts_[static_cast<std::size_t>(line)]
                              : text_.size();
  return text_.substr(begin, end - begin);
}

// The 0-based offset in the line of `needle` followed by a character that ends a name (or, for
// an attribute, by optional blanks and '='), at or after `from`; -1 when there is none.
int XmlPositions::find_on_line(int line, std::string_view needle, std::size_t from, bool element) const {
  const std::string_view text = line_text(line);
  for (std::size_t at = text.find(needle, from); at != std::string_view::npos; at = text.find(needle, at + 1)) {
    std::size_t after = at + needle.size();
    if (element) {
      if (after >= text.size() || std::strchr(" \t\r\n/>", text[after]) != nullptr) return static_cast<int>(at);
      continue;
    }
    const bool starts_name = at == 0 || std::strchr(" \t\r\n", text[at - 1]) != nullptr;
    while (after < text.size() && (text[after] == ' ' || text[after] == '\t')) ++after;
    if (starts_name && after < text.size() && text[after] == '=') return static_cast<int>(at);
  }
  return -1;
}

void XmlPositions::index(const tinyxml2::XMLElement* root) {
  std::vector<const tinyxml2::XMLElement*> stack{root};
  while (!stack.empty()) {
    const tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    at(e);
    std::vector<const tinyxml2::XMLElement*> children;
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) children.push_back(c);
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
}

SourceLocation XmlPositions::at(const tinyxml2::XMLElement* element) {
  const int line = element->GetLineNum();
  auto known = element_columns_.find(element);
  if (known != element_columns_.end()) return SourceLocation{file_, line, known->second};
  std::size_t& cursor = line_cursor_[line];
  const int found = find_on_line(line, std::string("<") + element->Name(), cursor, true);
  const int column = found < 0 ? 0 : found + 1;
  if (found >= 0) cursor = static_cast<std::size_t>(found) + 1;
  element_columns_.emplace(element, column);
  return SourceLocation{file_, line, column};
}

SourceLocation XmlPositions::at(const tinyxml2::XMLElement* element, const char* attribute) {
  const SourceLocation start = at(element);
  const tinyxml2::XMLAttribute* a = element->FindAttribute(attribute);
  if (!a) return start;
  const int line = a->GetLineNum();
  const std::size_t from = line == start.line && start.column > 0 ? static_cast<std::size_t>(start.column) : 0;
  const int found = find_on_line(line, attribute, from, false);
  return SourceLocation{file_, line, found < 0 ? 0 : found + 1};
}

}  // namespace bodyfmt::urdf_import
