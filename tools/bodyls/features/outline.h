#pragma once
// A forgiving reading of a Body file's YAML structure for the editor: block and flow
// mappings and sequences, scalars, anchors and aliases, each with its byte range. Unlike the
// loader's parser it never fails: half-typed text (an unclosed bracket, a key without a value,
// a stray line) still gives the structure around it, which is what hover and completion need
// while the user types. It does not interpret anything (no merge keys, no types).

#include "language_features.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::lsp {

/// Byte offsets of a text and the 1-based line and byte column of each.
class TextIndex {
 public:
  explicit TextIndex(std::string_view text);
  TextPoint point(std::size_t offset) const;
  /// The offset of `at`, clamped into the text (a column past a line's end is its end).
  std::size_t offset(TextPoint at) const;
  TextRange range(std::size_t begin, std::size_t end) const { return {point(begin), point(end)}; }
  std::size_t size() const { return size_; }

 private:
  std::vector<std::size_t> line_starts_;
  std::size_t size_ = 0;
};

struct OutlineNode;

struct OutlineEntry {
  std::string key;
  std::size_t key_begin = 0, key_end = 0;
  int value = -1;  ///< index of the value node
};

struct OutlineNode {
  enum Kind { kNull, kScalar, kMapping, kSequence, kAlias };
  Kind kind = kNull;
  std::size_t begin = 0, end = 0;  ///< the node's text (a null node: where it would be)
  std::string scalar;              ///< a scalar's text without quotes; an alias's name
  bool quoted = false;
  std::string anchor;  ///< `&name` on the node, else empty
  std::size_t anchor_begin = 0, anchor_end = 0;
  int indent = -1;  ///< a block collection's column (0-based); -1 for flow and scalars
  int parent = -1;
  std::vector<OutlineEntry> entries;  ///< a mapping's, in text order
  std::vector<int> items;             ///< a sequence's
};

class Outline {
 public:
  explicit Outline(std::string_view text);

  const std::vector<OutlineNode>& nodes() const { return nodes_; }
  const OutlineNode& node(int i) const { return nodes_[static_cast<std::size_t>(i)]; }
  int root() const { return root_; }
  std::string_view text() const { return text_; }

  /// The innermost node whose text holds `offset` (the root when none does).
  int node_at(std::size_t offset) const;
  /// The entry of mapping `map` named `key`, or nullptr.
  const OutlineEntry* find(int map, std::string_view key) const;
  /// The scalar of `map`'s entry `key`, or "" when absent or not a scalar.
  std::string scalar_of(int map, std::string_view key) const;
  /// The entry of its parent mapping whose value is node `i`, or nullptr.
  const OutlineEntry* entry_of(int i) const;

 private:
  friend class OutlineParser;
  std::string_view text_;
  std::vector<OutlineNode> nodes_;
  int root_ = 0;
};

}  // namespace bodyfmt::lsp
