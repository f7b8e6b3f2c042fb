#pragma once
// Line and column of XML elements and attributes. tinyxml2 keeps the line where each element
// and attribute starts, not the column, so the column is found in the text of that line: an
// element is the k-th "<name" on its line, where k counts the elements of the same name that
// come before it in document order on the same line; an attribute is the first "name=" after
// its element's start. The first element position asked for indexes the document once (each
// element's k, and per line and name the offsets of "<name"), so that a URDF with 100,000
// elements on one line costs a pass over it, not one per element (issue 34). Columns are
// 1-based byte offsets, as in the .body loader; 0 when the text does not show the name on
// that line (a CDATA or comment trick, or an entity-encoded name).
#include <bodyfmt/diagnostic.h>

#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace tinyxml2 {
class XMLElement;
}

namespace bodyfmt::urdf_import {

class XmlPositions {
 public:
  XmlPositions(std::string_view text, std::string file);

  /// Where `element` starts (its '<').
  SourceLocation at(const tinyxml2::XMLElement* element) const;
  /// Where the attribute `name` of `element` starts; the element's location when it has none.
  SourceLocation at(const tinyxml2::XMLElement* element, const char* attribute) const;
  /// A line alone (column 0).
  SourceLocation at_line(int line) const { return SourceLocation{file_, line, 0}; }
  const std::string& file() const { return file_; }

 private:
  std::string_view line_text(int line) const;
  int find_on_line(int line, std::string_view needle, std::size_t from, bool element) const;
  int element_column(const tinyxml2::XMLElement* element) const;
  void index_elements(const tinyxml2::XMLElement* any) const;

  std::string_view text_;
  std::string file_;
  std::vector<std::size_t> line_starts_;
  // Filled by index_elements: per element, how many elements of its name come before it on its
  // line; per line and element name, the 0-based offsets of "<name" on that line.
  mutable std::unordered_map<const tinyxml2::XMLElement*, std::size_t> same_name_before_;
  mutable std::map<std::pair<int, std::string>, std::vector<int>> openings_;
};

}  // namespace bodyfmt::urdf_import
