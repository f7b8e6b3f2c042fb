// complete (language_features.h). Half-typed text is the normal case: the word at the cursor
// is replaced by a placeholder key or value and the text read again with the forgiving
// outline, so the mapping the cursor is in is known even when the file does not parse.
#include "cursor.h"
#include "language_features.h"
#include "link_items.h"
#include "outline.h"
#include "schema.h"

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <system_error>

namespace bodyfmt::lsp {
namespace {

constexpr std::string_view kPlaceholder = "bodyls_cursor_";
constexpr std::size_t kMostFiles = 500;

bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; }

enum class Position { kNone, kKey, kValue, kAnchor };

/// Where the word at the cursor stands, from the line's text before it.
Position position_of(std::string_view before) {
  if (!before.empty() && before.back() == '*') return Position::kAnchor;
  std::vector<char> brackets;
  bool quoted = false;
  for (char c : before) {
    if (c == '"' || c == '\'') quoted = !quoted;
    if (quoted) continue;
    if (c == '[' || c == '{') brackets.push_back(c);
    if ((c == ']' || c == '}') && !brackets.empty()) brackets.pop_back();
    if (c == '#') return Position::kNone;
  }
  std::size_t end = before.size();
  while (end > 0 && (before[end - 1] == ' ' || before[end - 1] == '\t')) --end;
  const std::string_view trimmed = before.substr(0, end);
  if (trimmed.empty()) return Position::kKey;
  const char last = trimmed.back();
  if (last == ':') return Position::kValue;
  if (last == '-' && (trimmed.size() == 1 || trimmed[trimmed.size() - 2] == ' ' || trimmed[trimmed.size() - 2] == '-'))
    return brackets.empty() ? Position::kKey : Position::kValue;
  if (last == '{' || (last == ',' && !brackets.empty() && brackets.back() == '{')) return Position::kKey;
  if (last == '[' || (last == ',' && !brackets.empty() && brackets.back() == '[')) return Position::kValue;
  return Position::kNone;
}

/// The types a `type:` value may take where `mapping` stands (it has no type yet).
std::vector<std::string_view> type_values(const Outline& o, int mapping) {
  int holder_mapping = -1;
  const OutlineEntry* holder = holder_of(o, mapping, holder_mapping);
  if (!holder) return {};
  if (holder->key == "geometry") return geometry_type_names();
  if (holder->key == "elements" || node_kind(o, holder_mapping) == "elements") return element_type_names();
  if (holder->key == "links" && holder_mapping == o.root()) return {"Link", "SubBody", "ContinuousTrack", "Skip"};
  return {};
}

CompletionItem item(std::string label, std::string insert, std::string detail, CompletionKind kind, TextRange replace) {
  return CompletionItem{std::move(label), std::move(insert), std::move(detail), kind, replace};
}

void key_items(const Outline& o, int mapping, TextRange replace, std::vector<CompletionItem>& out) {
  const std::string kind = node_kind(o, mapping);
  std::set<std::string> present;
  for (const OutlineEntry& e : o.node(mapping).entries)
    if (e.key.rfind(kPlaceholder, 0) != 0) present.insert(e.key);
  if (kind == "elements") {
    for (std::string_view type : element_type_names())
      if (!present.count(std::string(type)))
        out.push_back(
            item(std::string(type), std::string(type) + ":", "an element of this type", CompletionKind::kKey, replace));
    return;
  }
  const BodyNode* node = table_node(kind);
  if (!node) {
    // An element or geometry without a type yet: its type comes first.
    if (!present.count("type") && (kind == "geometry" || !type_values(o, mapping).empty()))
      out.push_back(item("type", "type: ", "the node's type", CompletionKind::kKey, replace));
    return;
  }
  const std::string angle_unit = angle_unit_word(angle_mode(o));
  for (const BodyKey& key : node->keys) {
    bool taken = false;
    for (const std::string& p : present)
      if (const BodyKey* k = find_body_key(*node, p); k == &key) taken = true;
    if (taken) continue;
    out.push_back(item(std::string(key.name), std::string(key.name) + ": ", describe_body_key(key, angle_unit),
                       CompletionKind::kKey, replace));
  }
}

void file_items(const Document& document, const std::string& typed, TextRange replace,
                std::vector<CompletionItem>& out) {
  namespace fs = std::filesystem;
  const std::size_t slash = typed.rfind('/');
  const std::string folder_part = slash == std::string::npos ? "" : typed.substr(0, slash + 1);
  if (!folder_part.empty() && folder_part.front() == '/') return;  // absolute: not ours to list
  if (folder_part.find("://") != std::string::npos || folder_part.find('$') != std::string::npos) return;
  std::error_code ec;
  const fs::path base = fs::path(document.path).parent_path() / folder_part;
  if (!fs::is_directory(base, ec)) return;
  std::vector<std::pair<std::string, bool>> entries;
  for (fs::directory_iterator it(base, ec), end; !ec && it != end && entries.size() < kMostFiles; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name.front() == '.') continue;
    std::error_code type_ec;
    entries.emplace_back(name, it->is_directory(type_ec));
  }
  std::sort(entries.begin(), entries.end());
  for (const auto& [name, folder] : entries)
    out.push_back(item(folder_part + name + (folder ? "/" : ""), folder_part + name + (folder ? "/" : ""),
                       folder ? "folder" : "file", CompletionKind::kFile, replace));
}

void value_items(const Document& document, const Outline& o, int scalar, const std::string& typed, TextRange replace,
                 std::vector<CompletionItem>& out) {
  int mapping = -1;
  const OutlineEntry* holder = holder_of(o, scalar, mapping);
  if (!holder) return;
  const std::string kind = node_kind(o, mapping);
  if (names_a_link(kind, holder->key)) {
    const std::string own = holder->key == "parent" ? o.scalar_of(mapping, "name") : std::string();
    for (const LinkItem& link : link_items(o)) {
      if (link.name_text.empty() || link.name_text == own || link.name_text.rfind(kPlaceholder, 0) == 0) continue;
      out.push_back(item(link.name_text, link.name_text,
                         link.parent_text.empty() ? "root link" : "link, child of " + link.parent_text,
                         CompletionKind::kLinkName, replace));
    }
    return;
  }
  if (holder->key == "uri" || holder->key == "url" || holder->key == "model_file" || holder->key == "modelFile") {
    file_items(document, typed, replace, out);
    return;
  }
  std::vector<std::string_view> values;
  if (holder->key == "type") values = type_values(o, mapping);
  if (values.empty())
    if (const BodyNode* node = table_node(kind))
      if (const BodyKey* key = find_body_key(*node, holder->key)) values = key->values;
  for (std::string_view v : values)
    out.push_back(item(std::string(v), std::string(v), holder->key, CompletionKind::kValue, replace));
}

}  // namespace

std::vector<CompletionItem> complete(const Document& document, TextPoint point) {
  std::vector<CompletionItem> out;
  const std::string& text = document.text;
  const TextIndex index(text);
  const std::size_t offset = index.offset(point);
  std::size_t line_begin = offset;
  while (line_begin > 0 && text[line_begin - 1] != '\n') --line_begin;
  std::size_t word_begin = offset;
  while (word_begin > line_begin && is_word_char(text[word_begin - 1])) --word_begin;
  const std::string_view before(text.data() + line_begin, word_begin - line_begin);
  Position position = position_of(before);
  // A uri's value is a path: its word runs back to the value's start.
  std::size_t path_begin = word_begin;
  while (path_begin > line_begin && text[path_begin - 1] != ' ' && text[path_begin - 1] != ':' &&
         text[path_begin - 1] != '"' && text[path_begin - 1] != '\'' && text[path_begin - 1] != '[' &&
         text[path_begin - 1] != '{' && text[path_begin - 1] != ',')
    --path_begin;
  if (position == Position::kNone && path_begin < word_begin)
    position = position_of(std::string_view(text.data() + line_begin, path_begin - line_begin));
  if (position == Position::kNone) return out;

  if (position == Position::kAnchor) {
    const Outline outline(text);
    std::set<std::string> seen;
    for (const OutlineNode& node : outline.nodes())
      if (!node.anchor.empty() && seen.insert(node.anchor).second)
        out.push_back(
            item(node.anchor, node.anchor, "anchor", CompletionKind::kAnchor, index.range(word_begin, offset)));
    return out;
  }
  const std::string edited = text.substr(0, position == Position::kValue ? path_begin : word_begin) +
                             std::string(kPlaceholder) + (position == Position::kKey ? ": " : "") + text.substr(offset);
  const Outline outline(edited);
  for (std::size_t i = 0; i < outline.nodes().size(); ++i) {
    const OutlineNode& node = outline.node(static_cast<int>(i));
    if (node.parent == -2) continue;
    if (position == Position::kKey && node.kind == OutlineNode::kMapping) {
      for (const OutlineEntry& e : node.entries)
        if (e.key == kPlaceholder) {
          key_items(outline, static_cast<int>(i), index.range(word_begin, offset), out);
          return out;
        }
    }
    if (position == Position::kValue && node.kind == OutlineNode::kScalar && node.scalar.rfind(kPlaceholder, 0) == 0) {
      const std::string typed = text.substr(path_begin, offset - path_begin);
      const bool path = typed.find('/') != std::string::npos;
      value_items(document, outline, static_cast<int>(i), typed, index.range(path ? path_begin : word_begin, offset),
                  out);
      // A file's item replaces the whole path typed so far.
      for (CompletionItem& c : out)
        if (c.kind == CompletionKind::kFile) c.replace = index.range(path_begin, offset);
      return out;
    }
  }
  return out;
}

}  // namespace bodyfmt::lsp
