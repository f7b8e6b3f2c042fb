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

namespace {

// The element before `e` in document order (the previous sibling's last descendant, else the
// parent), or nullptr.
const tinyxml2::XMLElement* previous_in_document(const tinyxml2::XMLElement* e) {
  if (const tinyxml2::XMLElement* p = e->PreviousSiblingElement()) {
    while (const tinyxml2::XMLElement* last = p->LastChildElement()) p = last;
    return p;
  }
  const tinyxml2::XMLNode* parent = e->Parent();
  return parent ? parent->ToElement() : nullptr;
}

}  // namespace

int XmlPositions::element_column(const tinyxml2::XMLElement* element) const {
  const int line = element->GetLineNum();
  int before = 0;  // elements of the same name earlier on this line
  for (const tinyxml2::XMLElement* p = previous_in_document(element); p && p->GetLineNum() == line;
       p = previous_in_document(p))
    if (std::strcmp(p->Name(), element->Name()) == 0) ++before;
  const std::string needle = std::string("<") + element->Name();
  int found = find_on_line(line, needle, 0, true);
  for (; found >= 0 && before > 0; --before)
    found = find_on_line(line, needle, static_cast<std::size_t>(found) + 1, true);
  return found < 0 ? 0 : found + 1;
}

SourceLocation XmlPositions::at(const tinyxml2::XMLElement* element) const {
  return SourceLocation{file_, element->GetLineNum(), element_column(element)};
}

SourceLocation XmlPositions::at(const tinyxml2::XMLElement* element, const char* attribute) const {
  const SourceLocation start = at(element);
  const tinyxml2::XMLAttribute* a = element->FindAttribute(attribute);
  if (!a) return start;
  const int line = a->GetLineNum();
  const std::size_t from = line == start.line && start.column > 0 ? static_cast<std::size_t>(start.column) : 0;
  const int found = find_on_line(line, attribute, from, false);
  return SourceLocation{file_, line, found < 0 ? 0 : found + 1};
}

}  // namespace bodyfmt::urdf_import
