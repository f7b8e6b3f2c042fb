#pragma once
// The project's own YAML tree: every node keeps its position, every scalar stays a string
// (body-format-spec §1.1), aliases share one node, merge keys are already applied.
//
// The tree is compact and owned by its Document's arena: a 100,000-link file has about three
// million nodes, so a node is a fixed 56 bytes with its text and its children in one
// arena, nothing is freed one by one, and mapping keys are not nodes of their own.

#include <bodyfmt/diagnostic.h>

#include "yaml/arena.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>

namespace bodyfmt::yaml {

enum class NodeKind : std::uint8_t { kScalar, kSequence, kMapping };

class Node;

/// An edge to a node. When the node was reached through `*alias`, `alias_site` is where the
/// alias was written; `node->location` is always the anchor's (definition) site. Both sites
/// point into a Document (or into a node), which outlives every NodeRef read from it.
struct NodeRef {
  const Node* node = nullptr;
  const SourceLocation* alias_site = nullptr;
  /// Set by readers on the children of a node reached through an alias: the alias use site
  /// of the nearest such ancestor, so that a finding inside shared text can name the use
  /// that led to it.
  const SourceLocation* enclosing_alias = nullptr;

  /// `child` as seen through this node: it inherits this node's alias context.
  NodeRef child(const NodeRef& child) const {
    NodeRef result = child;
    if (result.alias_site == nullptr) result.enclosing_alias = alias_site != nullptr ? alias_site : enclosing_alias;
    return result;
  }

  const Node* operator->() const { return node; }
  const Node& operator*() const { return *node; }
  explicit operator bool() const { return node != nullptr; }
  /// Where the value appears from the reader's point of view: the alias use site if any.
  const SourceLocation& use_site() const;
};

/// Where a scalar's value is written, byte for byte: `text[begin, end)` of its file is exactly
/// the value (a plain scalar, or the inside of a quoted one without escapes), on the line of its
/// location, starting at byte column `column`. `begin == npos` when the value is not written
/// so (block and folded scalars, escapes, aliases, beyond the first 4 GiB of a file): a fix-it
/// cannot edit it in place.
struct TextSpan {
  static constexpr std::uint32_t npos = UINT32_MAX;
  std::uint32_t begin = npos;
  std::uint32_t end = npos;
  int column = 0;
  bool editable() const { return begin != npos; }
};

/// A node's children: a view of an array in the Document's arena.
template <typename T>
class Children {
 public:
  Children() = default;
  Children(const T* data, std::size_t size) : data_(data), size_(size) {}
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  const T& front() const { return data_[0]; }
  const T& back() const { return data_[size_ - 1]; }

 private:
  const T* data_ = nullptr;
  std::size_t size_ = 0;
};

struct MapEntry {
  std::string_view key;
  SourceLocation key_location;
  TextSpan key_span;    ///< the key's text (npos when written through an alias or with escapes)
  bool merged = false;  ///< came from a `<<` merge source rather than written locally
  NodeRef value;
};

class Node {
  // Data members are declared in layout order: a node is 56 bytes, and a 100,000-link file
  // holds about three million of them. The content (scalar text or children) is one field for
  // whichever kind this is.
 public:
  NodeKind kind = NodeKind::kScalar;
  bool plain = true;  ///< kScalar: false for quoted or block scalars

 private:
  std::uint32_t size_ = 0;  // parse_yaml refuses texts of 4 GiB or more

 public:
  SourceLocation location;  ///< 1-based position of the node's first character (or its anchor)
  TextSpan span;            ///< kScalar: where the value is written (fix-its edit it there)
  int expanded_depth = 0;   ///< 0 for a scalar, 1 + deepest child for a collection
  // Filled by parse_yaml when the node is finished, so that a document reaching this node through
  // any number of aliases is measured in O(1) per alias (billion-laughs guard, toolchain.md §3).
  std::size_t expanded_size = 0;  ///< 1 + sum over children, aliases in full; 0 = not finished

  bool is_scalar() const { return kind == NodeKind::kScalar; }
  bool is_sequence() const { return kind == NodeKind::kSequence; }
  bool is_mapping() const { return kind == NodeKind::kMapping; }
  /// kScalar: the value, in the Document's arena; `scalar().data()` is NUL-terminated. Empty
  /// for a collection.
  std::string_view scalar() const {
    return is_scalar() && data_ != nullptr ? std::string_view(static_cast<const char*>(data_), size_)
                                           : std::string_view("", 0);
  }
  /// kSequence: the items in order; empty otherwise.
  Children<NodeRef> items() const {
    return is_sequence() ? Children<NodeRef>(static_cast<const NodeRef*>(data_), size_) : Children<NodeRef>();
  }
  /// kMapping: file order; merge keys applied (local keys win, first merge source wins);
  /// duplicate keys collapsed (the last one wins, as in Choreonoid). The `<<` key is removed.
  /// Empty otherwise.
  Children<MapEntry> entries() const {
    return is_mapping() ? Children<MapEntry>(static_cast<const MapEntry*>(data_), size_) : Children<MapEntry>();
  }
  /// A plain, empty scalar or `~`/`null` (an absent value such as `key:`).
  bool is_null() const;
  /// Mapping lookup; nullptr entry when absent or when this is not a mapping.
  const MapEntry* find(std::string_view key) const;

  // For parse_yaml: the content lives in the Document's arena (Document::store).
  void set_scalar(std::string_view stored) { set(stored.data(), stored.size()); }
  void set_items(Children<NodeRef> stored) { set(stored.begin(), stored.size()); }
  void set_entries(Children<MapEntry> stored) { set(stored.begin(), stored.size()); }

 private:
  void set(const void* data, std::size_t size) {
    data_ = data;
    size_ = static_cast<std::uint32_t>(size);
  }
  const void* data_ = nullptr;
};

/// Takes the items of one top-level sequence while the document is parsed, each as soon as it
/// is finished, so that a reader can turn them into its own data and the tree need not keep
/// them: the links of a 100,000-link file are read one by one instead of as one tree.
class SequenceConsumer {
 public:
  virtual ~SequenceConsumer() = default;
  /// The top-level mapping key whose sequence value is offered.
  virtual std::string_view key() const = 0;
  /// `sequence` starts. `head` is a mapping of the top-level entries written before it, as far
  /// as they are known (merge keys not yet applied); it is valid during this call only.
  /// Returns false to leave the sequence in the tree as usual.
  virtual bool begin(const Node& head, const Node& sequence) = 0;
  /// A finished item, in order. Returns true when the item is consumed: it is then left out of
  /// the sequence, and its memory is reused unless it defines anchors or tags. The item is
  /// valid during this call only.
  virtual bool take(const NodeRef& item) = 0;
};

struct ParseOptions {
  /// Maximum number of nodes in the document as a consumer sees it, counting every alias
  /// expansion in full ("billion laughs" guard).
  std::size_t max_expanded_nodes = 40'000'000;
  /// Maximum nesting depth of sequences and mappings, counted through aliases.
  int max_depth = 200;
  /// Anchors defined elsewhere that this document may refer to (a YAML resource sees the
  /// main body file's anchors, body-format-spec §9.3). Not owned.
  const std::map<std::string, const Node*>* imported_anchors = nullptr;
  /// Offered the items of its key's sequence while they are parsed. Not owned.
  SequenceConsumer* stream = nullptr;
};

/// A parsed document. Owns every node, scalar and child array in one arena; NodeRefs point into it.
class Document {
 public:
  Document() = default;
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;

  NodeRef root;
  std::string file;
  std::map<std::string, const Node*> anchors;  ///< defined in this document
  std::size_t expanded_node_count = 0;

  Node* make_node();
  /// A copy of `text` in the arena, followed by a NUL (C parsers such as strtod read it in place).
  std::string_view store(std::string_view text);
  const SourceLocation* store(const SourceLocation& location);
  template <typename T>
  Children<T> store(const T* data, std::size_t size) {
    if (size == 0) return {};
    T* copy = static_cast<T*>(arena_.allocate(size * sizeof(T), alignof(T)));
    std::uninitialized_copy(data, data + size, copy);
    return Children<T>(copy, size);
  }
  /// The anchor a node was defined with ("" when none).
  std::string_view anchor_of(const Node* node) const;
  /// The tag as written ("!!str"; "" when none). Tags are kept, not used: the loader ignores them.
  std::string_view tag_of(const Node* node) const;
  void set_tag(const Node* node, std::string_view tag) { tags_[node] = store(tag); }
  std::size_t tag_count() const { return tags_.size(); }
  /// For parse_yaml: releases what was stored since `position` (a consumed sequence item).
  Arena::Mark mark() const { return arena_.mark(); }
  void rewind(Arena::Mark position) { arena_.rewind(position); }

 private:
  Arena arena_;
  std::unordered_map<const Node*, std::string_view> tags_;
};

/// Parses the first YAML document of `text`. Reports `yaml-*` diagnostics located in
/// `file_name`. Returns nullptr when nothing usable could be built: a syntax error, an
/// undefined alias, a redefined anchor, or a budget exceeded. Warnings (duplicate keys)
/// leave the document usable. A text without any document (empty, only comments) gives a
/// Document whose root is a plain empty scalar (`is_null()`) at 1:1, so callers need no null check.
std::unique_ptr<Document> parse_yaml(std::string_view text, const std::string& file_name, const ParseOptions& options,
                                     DiagnosticSink& sink);

}  // namespace bodyfmt::yaml
