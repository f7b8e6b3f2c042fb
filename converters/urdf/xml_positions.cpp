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

// Every element of the document of `any`, once, in document order: its ordinal among the
// elements of its name on its line, and the offsets of "<name" on each line that has one.
void XmlPositions::index_elements(const tinyxml2::XMLElement* any) const {
  std::map<std::pair<int, std::string>, std::size_t> seen;
  std::vector<const tinyxml2::XMLElement*> stack;
  for (const tinyxml2::XMLElement* e = any->GetDocument()->LastChildElement(); e; e = e->PreviousSiblingElement())
    stack.push_back(e);
  while (!stack.empty()) {
    const tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    std::pair<int, std::string> key(e->GetLineNum(), e->Name());
    same_name_before_[e] = seen[key]++;
    if (auto [it, fresh] = openings_.try_emplace(key); fresh) {
      const std::string needle = "<" + key.second;
      for (int at = find_on_line(key.first, needle, 0, true); at >= 0;
           at = find_on_line(key.first, needle, static_cast<std::size_t>(at) + 1, true))
        it->second.push_back(at);
    }
    for (const tinyxml2::XMLElement* c = e->LastChildElement(); c; c = c->PreviousSiblingElement()) stack.push_back(c);
  }
}

int XmlPositions::element_column(const tinyxml2::XMLElement* element) const {
  if (same_name_before_.empty()) index_elements(element);
  const auto before = same_name_before_.find(element);
  const auto openings = openings_.find({element->GetLineNum(), element->Name()});
  if (before == same_name_before_.end() || openings == openings_.end() || before->second >= openings->second.size())
    return 0;
  return openings->second[before->second] + 1;
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
