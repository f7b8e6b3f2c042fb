#pragma once
// Line and column of XML elements and attributes. tinyxml2 keeps the line where each element
// and attribute starts, not the column, so the column is found in the text: the first "<name"
// (for an element) or "name=" (for an attribute) on that line at or after the end of the
// previous match on that line. Elements are looked up in document order, so two elements of
// one name on one line get their own columns. Columns are 1-based byte offsets, as in the
// .body loader; 0 when the text does not show the name on that line (e.g. an attribute
// reported at its element because it is missing).
#include <bodyfmt/diagnostic.h>

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace tinyxml2 {
class XMLElement;
}

namespace bodyfmt::urdf_import {

class XmlPositions {
 public:
  XmlPositions(std::string_view text, std::string file);

  /// Finds the columns of `root` and every element under it, in document order (call once,
  /// before at(), so that elements sharing a line are told apart).
  void index(const tinyxml2::XMLElement* root);

  /// Where `element` starts (its '<').
  SourceLocation at(const tinyxml2::XMLElement* element);
  /// Where the attribute `name` of `element` starts; the element's location when it has none.
  SourceLocation at(const tinyxml2::XMLElement* element, const char* attribute);
  /// A line alone (column 0).
  SourceLocation at_line(int line) const { return SourceLocation{file_, line, 0}; }
  const std::string& file() const { return file_; }

 private:
  std::string_view line_text(int line) const;
  int find_on_line(int line, std::string_view needle, std::size_t from, bool element) const;

  std::string_view text_;
  std::string file_;
  std::vector<std::size_t> line_starts_;
  std::unordered_map<const tinyxml2::XMLElement*, int> element_columns_;
  std::unordered_map<int, std::size_t> line_cursor_;  ///< per line: where the next element search starts
};

}  // namespace bodyfmt::urdf_import
