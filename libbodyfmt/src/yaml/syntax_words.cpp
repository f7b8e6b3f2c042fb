#include "yaml/syntax_words.h"

#include "text/text_util.h"

#include <vector>

namespace bodyfmt::yaml {
namespace {

struct Line {
  std::string_view text;
  std::size_t indent = 0;  ///< spaces before the first other character
  bool content = false;    ///< neither blank nor a comment
};

Line read_line(std::string_view text) {
  Line line{text};
  while (line.indent < text.size() && text[line.indent] == ' ') ++line.indent;
  line.content = line.indent < text.size() && text[line.indent] != '#' && text[line.indent] != '\t';
  if (line.indent < text.size() && text[line.indent] == '\t') line.content = true;
  return line;
}

/// The columns a line may start at after `lines[0..last]`: the indentation of each line that
/// opens a level (less indented than every line below it), and for a `- ` item the column of
/// the mapping the item holds.
std::vector<std::size_t> open_levels(const std::vector<Line>& lines, std::size_t last) {
  std::vector<std::size_t> levels;
  std::size_t least = std::string_view::npos;
  for (std::size_t i = last + 1; i-- > 0;) {
    const Line& l = lines[i];
    if (!l.content || l.indent >= least) continue;
    least = l.indent;
    levels.push_back(l.indent);
    std::size_t key = l.indent;
    while (key + 1 < l.text.size() && l.text[key] == '-' && l.text[key + 1] == ' ') {
      key += 2;
      while (key < l.text.size() && l.text[key] == ' ') ++key;
      levels.push_back(key);
    }
  }
  return levels;
}

std::string spaces(std::size_t n) { return std::to_string(n) + (n == 1 ? " space" : " spaces"); }

}  // namespace

std::optional<SyntaxWords> syntax_in_words(std::string_view text, int line_number) {
  const std::vector<std::string_view> views = text::line_views(text);
  if (line_number < 1 || static_cast<std::size_t>(line_number) > views.size()) return std::nullopt;
  std::vector<Line> lines;
  lines.reserve(views.size());
  for (std::string_view v : views) lines.push_back(read_line(v));
  const std::size_t at = static_cast<std::size_t>(line_number - 1);

  // A tab in an indentation, on the line libyaml stopped at or on the lines just above it
  // (libyaml may stop at the end of the value the tab broke).
  for (std::size_t i = at + 1, seen = 0; i-- > 0 && seen < 3;) {
    const Line& l = lines[i];
    if (!l.content) continue;
    ++seen;
    if (l.indent < l.text.size() && l.text[l.indent] == '\t')
      return SyntaxWords{static_cast<int>(i + 1), static_cast<int>(l.indent + 1),
                         "a tab in the indentation of line " + std::to_string(i + 1) +
                             ": YAML indents with spaces only; replace the tab with spaces"};
  }

  const Line& here = lines[at];
  if (!here.content) return std::nullopt;
  std::size_t previous = at;
  while (previous-- > 0 && !lines[previous].content) {
  }
  if (previous == std::string_view::npos) return std::nullopt;
  const Line& above = lines[previous];
  const std::string where = "line " + std::to_string(at + 1);
  const std::string above_where = "line " + std::to_string(previous + 1);
  SyntaxWords words{line_number, static_cast<int>(here.indent + 1), ""};
  if (here.indent > above.indent) {
    // Deeper than the line above, which opens nothing: YAML reads it as more of that value.
    std::string_view opener = above.text.substr(0, above.text.find(" #"));
    while (!opener.empty() && opener.back() == ' ') opener.remove_suffix(1);
    if (!opener.empty() && (opener.back() == ':' || opener.back() == '-')) return std::nullopt;
    words.message = where + " is indented " + spaces(here.indent) + ", more than " + above_where + " above it (" +
                    std::to_string(above.indent) + "): the keys of one mapping start in the same column";
    return words;
  }
  const std::vector<std::size_t> levels = open_levels(lines, previous);
  for (std::size_t level : levels)
    if (level == here.indent) return std::nullopt;  // it lines up with something: another problem
  // The nearest deeper level is the mapping the line was most probably meant to belong to.
  std::size_t meant = above.indent;
  for (std::size_t level : levels)
    if (level > here.indent && level < meant) meant = level;
  words.message = where + " is indented " + spaces(here.indent) + ", which lines up with no line above it; the keys " +
                  "it follows (" + above_where + ") are indented " + std::to_string(meant) +
                  ": the keys of one mapping start in the same column";
  return words;
}

std::optional<SyntaxWords> colon_in_value(std::string_view text, int line_number, int column) {
  const std::vector<std::string_view> views = text::line_views(text);
  if (line_number < 1 || static_cast<std::size_t>(line_number) > views.size() || column < 1) return std::nullopt;
  std::string_view line = views[static_cast<std::size_t>(line_number - 1)];
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const std::size_t colon = static_cast<std::size_t>(column - 1);
  if (colon >= line.size() || line[colon] != ':') return std::nullopt;
  // The line's own key: after the indentation and any "- " of list items.
  std::size_t key = 0;
  while (key < line.size() && line[key] == ' ') ++key;
  while (key + 1 < line.size() && line[key] == '-' && line[key + 1] == ' ') {
    key += 2;
    while (key < line.size() && line[key] == ' ') ++key;
  }
  const std::size_t separator = line.find(": ", key);
  if (separator == std::string_view::npos || separator >= colon) return std::nullopt;
  const std::string_view name = line.substr(key, separator - key);
  if (name.empty() || name.find_first_of("\"'{}[],#&*!|>%@`") != std::string_view::npos) return std::nullopt;
  std::size_t value_begin = separator + 2;
  while (value_begin < colon && line[value_begin] == ' ') ++value_begin;
  if (value_begin >= colon) return std::nullopt;
  // Only a plain value: a quoted or flow one, an anchor, alias or tag is another matter.
  if (std::string_view("\"'{}[]&*!|>%@`#").find(line[value_begin]) != std::string_view::npos) return std::nullopt;
  const std::string_view before = line.substr(value_begin, colon - value_begin);
  std::size_t after = colon + 1;
  while (after < line.size() && line[after] == ' ') ++after;
  const bool ends = after == line.size() || line[after] == '#';
  const std::size_t line_start = static_cast<std::size_t>(line.data() - text.data());
  SyntaxWords words{line_number, column, ""};
  if (ends) {
    std::string_view meant = before;
    while (!meant.empty() && meant.back() == ' ') meant.remove_suffix(1);
    words.message = "a value cannot end with ':': YAML reads \"" + std::string(before) +
                    ":\" as the key of a new mapping, which cannot stand where the value of \"" + std::string(name) +
                    "\" is; write \"" + std::string(name) + ": " + std::string(meant) + "\"";
    words.hint = "remove the ':' after " + std::string(meant);
    words.edit = SyntaxWords::Edit{line_start + colon, line_start + colon + 1, ""};
  } else {
    std::size_t value_end = after;
    while (value_end < line.size() && !(line[value_end] == '#' && line[value_end - 1] == ' ')) ++value_end;
    while (value_end > after && line[value_end - 1] == ' ') --value_end;
    const std::string_view value = line.substr(value_begin, value_end - value_begin);
    words.message = "the value of \"" + std::string(name) + "\" holds \": \", which YAML reads as the start of a " +
                    "mapping where a value must be; quote the value: " + std::string(name) + ": \"" +
                    std::string(value) + "\"";
    words.hint = "quote the value";
  }
  return words;
}

}  // namespace bodyfmt::yaml
