// Text -> yaml::Node tree through yaml-cpp's event API (style.md §2.1). The DOM API (YAML::Load)
// is not used: a node reached through an alias carries only the anchor's mark, never the use
// site (toolchain.md §3), and it offers no hook for the expansion and depth budgets.

#include "yaml/yaml_node.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <algorithm>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace bodyfmt::yaml {
namespace {

// Stops yaml-cpp from inside the handler once a fatal diagnostic has been queued.
struct ParseAborted {};

// yaml-cpp resolves aliases itself and throws on an anchor it has not seen, so an alias to an
// imported anchor (body-format-spec §9.3) cannot reach the handler as an alias. parse_yaml
// rewrites the `*` of such an alias into this letter, which turns `*NAME` into the plain scalar
// `zNAME` of the same extent, and re-parses; the handler then swaps that scalar for the alias.
constexpr char kImportedAliasMarker = 'z';

// Keyed by the byte offset of the rewritten `*` in the text.
struct ImportedAliasSite {
  std::string name;
  const Node* node = nullptr;
};

bool is_blank_or_break(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool is_flow_indicator(char c) { return c == ',' || c == '[' || c == ']' || c == '{' || c == '}'; }

// What yaml-cpp 0.7 reads as an anchor or alias name: up to a blank or a flow indicator.
std::size_t name_end(std::string_view text, std::size_t pos) {
  while (pos < text.size() && !is_blank_or_break(text[pos]) && !is_flow_indicator(text[pos])) ++pos;
  return pos;
}

std::size_t saturating_add(std::size_t a, std::size_t b) {
  return a > std::numeric_limits<std::size_t>::max() - b ? std::numeric_limits<std::size_t>::max()
                                                         : a + b;
}

// The events give neither the tag as written nor the quoting style, so both are read back from
// the text: a node's mark points at its first property (`&a`, `!tag`) or at its content.
struct NodeText {
  std::string tag;
  std::size_t content = 0;  // offset of the first content character
};

NodeText scan_node_text(std::string_view text, std::size_t pos) {
  NodeText result;
  while (pos < text.size() && (text[pos] == '&' || text[pos] == '!')) {
    std::size_t end = pos + 1;
    if (text[pos] == '!' && end < text.size() && text[end] == '<') {
      end = text.find('>', end);
      end = end == std::string_view::npos ? text.size() : end + 1;
    } else {
      end = name_end(text, end);
    }
    if (text[pos] == '!') result.tag = std::string(text.substr(pos, end - pos));
    pos = end;
    while (pos < text.size()) {
      if (is_blank_or_break(text[pos])) {
        ++pos;
      } else if (text[pos] == '#') {
        while (pos < text.size() && text[pos] != '\n') ++pos;
      } else {
        break;
      }
    }
  }
  result.content = pos;
  return result;
}

// yaml-cpp reports `~`/`null` without their text; recover the spelling so the scalar keeps it.
std::string_view null_word_at(std::string_view text, std::size_t pos) {
  for (std::string_view word : {"~", "null", "Null", "NULL"}) {
    if (text.substr(pos, word.size()) != word) continue;
    std::size_t after = pos + word.size();
    if (after == text.size() || is_blank_or_break(text[after]) || text[after] == ',' ||
        text[after] == ']' || text[after] == '}' || text[after] == ':') {
      return word;
    }
  }
  return {};
}

// True when the text at `pos` (after spaces) is the `:` of a mapping key.
bool followed_by_colon(std::string_view text, std::size_t pos) {
  while (pos < text.size() && (text[pos] == ' ' || text[pos] == '\t')) ++pos;
  return pos < text.size() && text[pos] == ':';
}

class TreeBuilder final : public YAML::EventHandler {
 public:
  TreeBuilder(std::string_view text, std::size_t bom_size, const std::string& file,
              const ParseOptions& options, Document& document,
              const std::unordered_map<std::size_t, ImportedAliasSite>& imported_sites)
      : text_(text),
        bom_size_(bom_size),
        file_(file),
        options_(options),
        document_(document),
        imported_sites_(imported_sites) {}

  std::vector<Diagnostic>& diagnostics() { return diagnostics_; }
  bool failed() const { return failed_; }
  NodeRef root() const { return root_; }

  SourceLocation location(const YAML::Mark& mark) const {
    if (mark.is_null()) return SourceLocation{file_, 0, 0};
    return SourceLocation{file_, mark.line + 1, mark.column + 1};  // yaml-cpp marks are 0-based
  }

  void report(Severity severity, std::string rule_id, SourceLocation location, std::string message,
              std::string fix_hint = {}) {
    Diagnostic diagnostic;
    diagnostic.severity = severity;
    diagnostic.rule_id = std::move(rule_id);
    diagnostic.message = std::move(message);
    diagnostic.location = std::move(location);
    diagnostic.fix_hint = std::move(fix_hint);
    diagnostics_.push_back(std::move(diagnostic));
    if (severity == Severity::kFatal) failed_ = true;
  }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    Node* node = begin_node(NodeKind::kScalar, mark, anchor);
    // A missing value is reported at the next token (often the next line's key): `a:\nnull: 1`
    // gives the value of `a` the mark of `null`. A null word followed by `:` is that next key.
    std::size_t content = scan_node_text(text_, offset(mark)).content;
    std::string_view word = null_word_at(text_, content);
    bool key = in_key_position();
    if (!key && !word.empty() && followed_by_colon(text_, content + word.size())) word = {};
    node->scalar = std::string(word);
    if (word.empty() && !key && anchor == YAML::NullAnchor && !frames_.empty() &&
        frames_.back().node->is_mapping()) {
      node->location = frames_.back().key_location;  // `key:` with nothing after it
    }
    finish_scalar(node);
  }

  void OnScalar(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                const std::string& value) override {
    auto site = imported_sites_.find(offset(mark));
    if (site != imported_sites_.end()) {
      if (value != kImportedAliasMarker + site->second.name) {
        // The rewrite changed how the line parses (e.g. `*a:b`); give up on this alias.
        report(Severity::kError, "yaml-undefined-alias", location(mark),
               "alias \"*" + site->second.name + "\" cannot be resolved here");
        failed_ = true;
      }
      add_alias(site->second.node, mark);
      return;
    }
    Node* node = begin_node(NodeKind::kScalar, mark, anchor);
    node->scalar = value;
    finish_scalar(node);
  }

  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const Node* target = anchor < anchor_nodes_.size() ? anchor_nodes_[anchor] : nullptr;
    if (target == nullptr) {  // yaml-cpp throws before this; kept as a guard
      report(Severity::kFatal, "yaml-undefined-alias", location(mark), "undefined alias");
      throw ParseAborted{};
    }
    add_alias(target, mark);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value /*style*/) override {
    begin_collection(begin_node(NodeKind::kSequence, mark, anchor));
  }
  void OnSequenceEnd() override { end_collection(); }

  void OnMapStart(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value /*style*/) override {
    begin_collection(begin_node(NodeKind::kMapping, mark, anchor));
  }
  void OnMapEnd() override { end_collection(); }

  void OnAnchor(const YAML::Mark& /*mark*/, const std::string& anchor_name) override {
    pending_anchor_ = anchor_name;
  }

 private:
  struct MergeSlot {
    std::size_t position = 0;  // number of local entries written before the `<<`
    std::vector<NodeRef> sources;
  };
  enum class KeyState { kNormal, kMerge, kSkip };
  struct Frame {
    Node* node = nullptr;
    bool is_key = false;             // the collection itself is a (complex) mapping key
    std::size_t count_at_start = 0;  // expanded_count_ before this collection was opened
    // Mapping state.
    bool expecting_key = true;
    KeyState key_state = KeyState::kNormal;
    std::string key;
    SourceLocation key_location;
    std::unordered_map<std::string, std::pair<std::size_t, int>> local_keys;  // index, first line
    std::vector<MergeSlot> merges;
  };

  std::size_t offset(const YAML::Mark& mark) const {
    // yaml-cpp skips a UTF-8 byte order mark without counting it in Mark::pos. Positions in
    // UTF-16/32 input count transcoded bytes, hence the clamp (the text scans then find nothing).
    if (mark.pos < 0) return text_.size();
    return std::min(static_cast<std::size_t>(mark.pos) + bom_size_, text_.size());
  }

  bool in_key_position() const {
    return !frames_.empty() && frames_.back().node->is_mapping() && frames_.back().expecting_key;
  }

  Node* begin_node(NodeKind kind, const YAML::Mark& mark, YAML::anchor_t anchor) {
    Node* node = document_.make_node();
    node->kind = kind;
    node->location = location(mark);
    NodeText node_text = scan_node_text(text_, offset(mark));
    node->tag = std::move(node_text.tag);
    if (kind == NodeKind::kScalar && node_text.content < text_.size()) {
      char first = text_[node_text.content];
      node->plain = !(first == '"' || first == '\'' || first == '|' || first == '>');
    }
    if (anchor != YAML::NullAnchor) define_anchor(node, anchor);
    if (!in_key_position()) add_to_budget(1, node->location, false);
    return node;
  }

  void define_anchor(Node* node, YAML::anchor_t anchor) {
    node->anchor = std::move(pending_anchor_);
    pending_anchor_.clear();
    if (anchor_nodes_.size() <= anchor) anchor_nodes_.resize(anchor + 1, nullptr);
    anchor_nodes_[anchor] = node;  // yaml-cpp resolves later aliases to the newest definition
    auto [it, inserted] = document_.anchors.emplace(node->anchor, node);
    if (!inserted) {
      // body-format-spec §1.4: Choreonoid rejects a duplicated anchor, stricter than YAML 1.2.
      report(Severity::kError, "yaml-anchor-redefined", node->location,
             "anchor \"" + node->anchor + "\" is already defined at line " +
                 std::to_string(it->second->location.line),
             "give each anchor a unique name");
      failed_ = true;
    }
  }

  void add_to_budget(std::size_t nodes, const SourceLocation& where, bool via_alias) {
    expanded_count_ = saturating_add(expanded_count_, nodes);
    if (expanded_count_ <= options_.max_expanded_nodes) return;
    std::string limit = std::to_string(options_.max_expanded_nodes);
    report(Severity::kFatal, "yaml-alias-expansion", where,
           via_alias ? "expanding this alias makes the document larger than the limit of " + limit +
                           " nodes (alias bomb?)"
                     : "the document has more than the limit of " + limit + " nodes",
           "if the file is legitimate, raise the limit (--max-yaml-nodes, LoadOptions::max_expanded_yaml_nodes)");
    throw ParseAborted{};
  }

  void check_depth(int depth, const SourceLocation& where) {
    if (depth <= options_.max_depth) return;
    report(Severity::kFatal, "yaml-depth", where,
           "nesting is deeper than the limit of " + std::to_string(options_.max_depth) +
               " levels (counted through aliases)",
           "if the file is legitimate, raise the limit (ParseOptions::max_depth)");
    throw ParseAborted{};
  }

  void add_alias(const Node* target, const YAML::Mark& mark) {
    SourceLocation site = location(mark);
    if (target->expanded_size == 0) {
      // `&a [*a]`: yaml-cpp registers the anchor before its content, so this would be a cycle.
      report(Severity::kFatal, "yaml-recursive-alias", site,
             "alias \"*" + target->anchor + "\" refers to a node that contains it (defined at line " +
                 std::to_string(target->location.line) + ")");
      throw ParseAborted{};
    }
    if (!in_key_position()) add_to_budget(target->expanded_size, site, true);
    check_depth(static_cast<int>(frames_.size()) + target->expanded_depth, site);
    deliver(NodeRef{target, std::move(site), std::nullopt});
  }

  void finish_scalar(Node* node) {
    node->expanded_size = 1;
    node->expanded_depth = 0;
    deliver(NodeRef{node, std::nullopt, std::nullopt});
  }

  void begin_collection(Node* node) {
    Frame frame;
    frame.node = node;
    frame.is_key = in_key_position();
    frame.count_at_start = expanded_count_ - (frame.is_key ? 0 : 1);
    frames_.push_back(std::move(frame));
    check_depth(static_cast<int>(frames_.size()), node->location);
  }

  void end_collection() {
    Frame frame = std::move(frames_.back());
    frames_.pop_back();
    Node* node = frame.node;
    if (node->is_mapping() && !frame.merges.empty()) apply_merges(frame);
    std::size_t size = 1;
    int depth = 0;
    auto measure = [&](const NodeRef& child) {
      size = saturating_add(size, child->expanded_size);
      depth = std::max(depth, child->expanded_depth);
    };
    for (const NodeRef& item : node->items) measure(item);
    for (const MapEntry& entry : node->entries) measure(entry.value);
    node->expanded_size = size;
    node->expanded_depth = depth + 1;
    // The running count was provisional (merge sources and overwritten duplicates counted in
    // full); replace it by the exact size now that the collection is final.
    expanded_count_ = frame.count_at_start;
    if (!frame.is_key) add_to_budget(size, node->location, false);
    deliver(NodeRef{node, std::nullopt, std::nullopt});
  }

  void deliver(NodeRef ref) {
    if (frames_.empty()) {
      root_ = std::move(ref);
      return;
    }
    Frame& frame = frames_.back();
    if (frame.node->is_sequence()) {
      frame.node->items.push_back(std::move(ref));
    } else if (frame.expecting_key) {
      accept_key(frame, ref);
      frame.expecting_key = false;
    } else {
      accept_value(frame, std::move(ref));
      frame.expecting_key = true;
    }
  }

  void accept_key(Frame& frame, const NodeRef& ref) {
    frame.key_location = ref.use_site();
    if (!ref->is_scalar()) {
      report(Severity::kError, "yaml-complex-key", frame.key_location,
             "a mapping key must be a scalar, not a " +
                 std::string(ref->is_mapping() ? "mapping" : "sequence"));
      frame.key_state = KeyState::kSkip;
    } else if (ref->scalar.empty()) {
      // body-format-spec §1.8: Choreonoid reports "empty key".
      report(Severity::kError, "yaml-empty-key", frame.key_location, "empty mapping key");
      frame.key_state = KeyState::kSkip;
    } else {
      // body-format-spec §1.5: Choreonoid compares the key text, whatever its quoting.
      frame.key_state = ref->scalar == "<<" ? KeyState::kMerge : KeyState::kNormal;
      frame.key = ref->scalar;
    }
  }

  void accept_value(Frame& frame, NodeRef value) {
    if (frame.key_state == KeyState::kSkip) return;
    if (frame.key_state == KeyState::kMerge) {
      add_merge(frame, value);
      return;
    }
    std::vector<MapEntry>& entries = frame.node->entries;
    auto [it, inserted] = frame.local_keys.try_emplace(
        frame.key, std::make_pair(entries.size(), frame.key_location.line));
    if (inserted) {
      entries.push_back(MapEntry{frame.key, frame.key_location, std::move(value), false});
      return;
    }
    // body-format-spec §1.6: the last one wins (WAREC1's `type: Collision` then `type: Group`).
    report(Severity::kWarning, "yaml-duplicate-key", frame.key_location,
           "duplicate key \"" + frame.key + "\" (first at line " +
               std::to_string(it->second.second) + "); the last value wins",
           "remove one of the two entries");
    MapEntry& entry = entries[it->second.first];
    entry.key_location = frame.key_location;
    entry.value = std::move(value);
  }

  // body-format-spec §1.5: the value of `<<` is a mapping or a sequence of mappings.
  void add_merge(Frame& frame, const NodeRef& value) {
    MergeSlot slot;
    slot.position = frame.node->entries.size();
    if (value->is_mapping()) {
      slot.sources.push_back(value);
    } else if (value->is_sequence()) {
      for (const NodeRef& item : value->items) {
        if (item->is_mapping()) {
          slot.sources.push_back(item);
        } else {
          report(Severity::kError, "yaml-merge-invalid", item.use_site(),
                 "an element to merge by the \"<<\" key must be a mapping");
        }
      }
    } else {
      report(Severity::kError, "yaml-merge-invalid", value.use_site(),
             "a value to merge by the \"<<\" key must be a mapping or a sequence of mappings");
    }
    frame.merges.push_back(std::move(slot));
  }

  // Local keys win wherever they are written; among merge sources the first one wins. Merged
  // entries take the place of the `<<` entry, which is dropped. Sources are finished nodes, so
  // their own merges are already applied (nested merges need no recursion).
  void apply_merges(Frame& frame) {
    std::vector<MapEntry> locals = std::move(frame.node->entries);
    std::unordered_set<std::string> present;
    for (const MapEntry& entry : locals) present.insert(entry.key);
    std::vector<MapEntry> merged;
    std::size_t next_local = 0;
    for (const MergeSlot& slot : frame.merges) {
      while (next_local < slot.position) merged.push_back(std::move(locals[next_local++]));
      for (const NodeRef& source : slot.sources) {
        for (const MapEntry& entry : source->entries) {
          if (!present.insert(entry.key).second) continue;
          merged.push_back(MapEntry{entry.key, entry.key_location, entry.value, true});
        }
      }
    }
    while (next_local < locals.size()) merged.push_back(std::move(locals[next_local++]));
    frame.node->entries = std::move(merged);
  }

  std::string_view text_;
  std::size_t bom_size_;
  const std::string& file_;
  const ParseOptions& options_;
  Document& document_;
  const std::unordered_map<std::size_t, ImportedAliasSite>& imported_sites_;

  std::vector<Diagnostic> diagnostics_;
  bool failed_ = false;
  NodeRef root_;
  std::vector<Frame> frames_;
  std::vector<const Node*> anchor_nodes_;  // by yaml-cpp anchor id
  std::string pending_anchor_;
  std::size_t expanded_count_ = 0;  // nodes seen so far, aliases expanded (provisional)
};

enum class Outcome { kDone, kRetry };

// One pass over `text`. On an alias to an imported anchor, records the site and asks for a retry.
Outcome parse_once(std::string& text, std::size_t bom_size, const std::string& file_name,
                   const ParseOptions& options,
                   std::unordered_map<std::size_t, ImportedAliasSite>& imported_sites,
                   std::unique_ptr<Document>& document, std::vector<Diagnostic>& diagnostics) {
  document = std::make_unique<Document>();
  document->file = file_name;
  TreeBuilder builder(text, bom_size, file_name, options, *document, imported_sites);
  auto finish = [&](bool usable) {
    diagnostics = std::move(builder.diagnostics());
    if (!usable || builder.failed()) document.reset();
  };
  try {
    std::istringstream stream(text);
    YAML::Parser parser(stream);
    // Only the first document is used (body-format-spec §1.8); later ones are not even scanned.
    if (!parser.HandleNextDocument(builder) || !builder.root()) {
      Node* empty = document->make_node();
      empty->location = SourceLocation{file_name, 1, 1};
      empty->expanded_size = 1;
      document->root = NodeRef{empty, std::nullopt, std::nullopt};
    } else {
      document->root = builder.root();
    }
    document->expanded_node_count = document->root->expanded_size;
    finish(true);
    return Outcome::kDone;
  } catch (const ParseAborted&) {
    finish(false);
    return Outcome::kDone;
  } catch (const YAML::DeepRecursion& e) {
    builder.report(Severity::kFatal, "yaml-depth", builder.location(e.mark),
                   "nesting is deeper than yaml-cpp's limit of " + std::to_string(e.depth()) +
                       " levels");
    finish(false);
    return Outcome::kDone;
  } catch (const YAML::ParserException& e) {
    const bool undefined_alias = e.msg.rfind(YAML::ErrorMsg::UNKNOWN_ANCHOR, 0) == 0;
    const std::size_t at = e.mark.pos < 0 ? text.size() : e.mark.pos + bom_size;
    if (undefined_alias && at < text.size() && text[at] == '*') {
      std::string name(std::string_view(text).substr(at + 1, name_end(text, at + 1) - at - 1));
      const Node* imported = nullptr;
      if (options.imported_anchors != nullptr) {
        auto it = options.imported_anchors->find(name);
        if (it != options.imported_anchors->end()) imported = it->second;
      }
      if (imported != nullptr && imported->expanded_size != 0) {
        text[at] = kImportedAliasMarker;
        imported_sites[at] = ImportedAliasSite{std::move(name), imported};
        return Outcome::kRetry;
      }
      builder.report(Severity::kError, "yaml-undefined-alias", builder.location(e.mark),
                     "alias \"*" + name + "\" refers to an anchor that is not defined before it",
                     "define the anchor (&" + name + ") before its first use");
    } else {
      builder.report(Severity::kFatal, "yaml-syntax", builder.location(e.mark), e.msg);
    }
    finish(false);
    return Outcome::kDone;
  } catch (const std::exception& e) {
    builder.report(Severity::kFatal, "yaml-syntax", SourceLocation{file_name, 0, 0},
                   std::string("cannot read the YAML text: ") + e.what());
    finish(false);
    return Outcome::kDone;
  }
}

}  // namespace

std::unique_ptr<Document> parse_yaml(std::string_view text, const std::string& file_name,
                                     const ParseOptions& options, DiagnosticSink& sink) {
  std::unique_ptr<Document> document;
  std::vector<Diagnostic> diagnostics;
  try {
    std::string work(text);
    const std::size_t bom_size = work.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
    std::unordered_map<std::size_t, ImportedAliasSite> imported_sites;
    // Each retry resolves one more imported-alias site, so this ends after at most as many
    // passes as there are such sites (usually zero; quadratic only for a file full of them).
    while (parse_once(work, bom_size, file_name, options, imported_sites, document, diagnostics) ==
           Outcome::kRetry) {
    }
  } catch (...) {  // e.g. std::bad_alloc: never throw across the API (style.md §2.4)
    document.reset();
    Diagnostic diagnostic;
    diagnostic.severity = Severity::kFatal;
    diagnostic.rule_id = "yaml-syntax";
    diagnostic.message = "cannot read the YAML text (out of memory?)";
    diagnostic.location = SourceLocation{file_name, 0, 0};
    diagnostics.push_back(std::move(diagnostic));
  }
  // Diagnostics are held back until the last pass so that a retry does not repeat them.
  for (Diagnostic& diagnostic : diagnostics) sink.report(std::move(diagnostic));
  return document;
}

}  // namespace bodyfmt::yaml
