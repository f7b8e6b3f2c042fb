#pragma once
// Line and column of XML elements and attributes. tinyxml2 keeps the line where each element
// and attribute starts, not the column, so the column is found in the text of that line: an
// element is the k-th "<name" on its line, where k counts the elements of the same name that
// come before it in document order on the same line; an attribute is the first "name=" after
// its element's start. Nothing is indexed ahead, so a position costs only the elements on its
// line. Columns are 1-based byte offsets, as in the .body loader; 0 when the text does not
// show the name on that line (a CDATA or comment trick, or an entity-encoded name).
#include <bodyfmt/diagnostic.h>

#include <string>
#include <string_view>
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

  std::string_view text_;
  std::string file_;
  std::vector<std::size_t> line_starts_;
};

}  // namespace bodyfmt::urdf_import
