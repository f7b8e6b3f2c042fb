#pragma once
// The project's own YAML tree: every node keeps its position, every scalar stays a string
// (body-format-spec §1.1), aliases share one node, merge keys are already applied.

#include <bodyfmt/diagnostic.h>

#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::yaml {

enum class NodeKind { kScalar, kSequence, kMapping };

struct Node;

/// An edge to a node. When the node was reached through `*alias`, `alias_site` is where the
/// alias was written; `node->location` is always the anchor's (definition) site.
struct NodeRef {
  const Node* node = nullptr;
  std::optional<SourceLocation> alias_site;
  /// Set by readers on the children of a node reached through an alias: the alias use site
  /// of the nearest such ancestor, so that a finding inside shared text can name the use
  /// that led to it.
  std::optional<SourceLocation> enclosing_alias;

  /// `child` as seen through this node: it inherits this node's alias context.
  NodeRef child(const NodeRef& child) const {
    NodeRef result = child;
    if (!result.alias_site) result.enclosing_alias = alias_site ? alias_site : enclosing_alias;
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
/// so (block and folded scalars, escapes, aliases): a fix-it cannot edit it in place.
struct TextSpan {
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  std::size_t begin = npos;
  std::size_t end = npos;
  int column = 0;
  bool editable() const { return begin != npos; }
};

struct MapEntry {
  std::string key;
  SourceLocation key_location;
  TextSpan key_span;  ///< the key's text (npos when written through an alias or with escapes)
  NodeRef value;
  bool merged = false;  ///< came from a `<<` merge source rather than written locally
};

struct Node {
  NodeKind kind = NodeKind::kScalar;
  SourceLocation location;  ///< 1-based position of the node's first character (or its anchor)
  std::string anchor;       ///< empty when not anchored
  std::string tag;          ///< as written ("!!str"), ignored by the loader

  // kScalar
  std::string scalar;
  bool plain = true;  ///< false for quoted or block scalars
  TextSpan span;      ///< where `scalar` is written (fix-its edit it there)
  // kSequence
  std::vector<NodeRef> items;
  // kMapping: file order; merge keys applied (local keys win, first merge source wins);
  // duplicate keys collapsed (the last one wins, as in Choreonoid). The `<<` key is removed.
  std::vector<MapEntry> entries;

  // Filled by parse_yaml when the node is finished, so that a document reaching this node through
  // any number of aliases is measured in O(1) per alias (billion-laughs guard, toolchain.md §3).
  std::size_t expanded_size = 0;  ///< 1 + sum over children, aliases in full; 0 = not finished
  int expanded_depth = 0;         ///< 0 for a scalar, 1 + deepest child for a collection

  bool is_scalar() const { return kind == NodeKind::kScalar; }
  bool is_sequence() const { return kind == NodeKind::kSequence; }
  bool is_mapping() const { return kind == NodeKind::kMapping; }
  /// A plain, empty scalar or `~`/`null` (an absent value such as `key:`).
  bool is_null() const;
  /// Mapping lookup; nullptr entry when absent or when this is not a mapping.
  const MapEntry* find(std::string_view key) const;
};

struct ParseOptions {
  /// Maximum number of nodes in the document as a consumer sees it, counting every alias
  /// expansion in full ("billion laughs" guard).
  std::size_t max_expanded_nodes = 10'000'000;
  /// Maximum nesting depth of sequences and mappings, counted through aliases.
  int max_depth = 200;
  /// Anchors defined elsewhere that this document may refer to (a YAML resource sees the
  /// main body file's anchors, body-format-spec §9.3). Not owned.
  const std::map<std::string, const Node*>* imported_anchors = nullptr;
};

/// A parsed document. Owns every node; NodeRefs point into it.
class Document {
 public:
  NodeRef root;
  std::string file;
  std::map<std::string, const Node*> anchors;  ///< defined in this document
  std::size_t expanded_node_count = 0;

  Node* make_node();

 private:
  std::deque<Node> nodes_;  ///< chunked: stable addresses without one allocation per node
};

/// Parses the first YAML document of `text`. Reports `yaml-*` diagnostics located in
/// `file_name`. Returns nullptr when nothing usable could be built: a syntax error, an
/// undefined alias, a redefined anchor, or a budget exceeded. Warnings (duplicate keys)
/// leave the document usable. A text without any document (empty, only comments) gives a
/// Document whose root is a plain empty scalar (`is_null()`) at 1:1, so callers need no null check.
std::unique_ptr<Document> parse_yaml(std::string_view text, const std::string& file_name, const ParseOptions& options,
                                     DiagnosticSink& sink);

}  // namespace bodyfmt::yaml
