// Text -> yaml::Node tree through libyaml's event API, the parser Choreonoid itself uses
// (body-format-spec §1), so what it accepts and rejects is Choreonoid's. It replaced yaml-cpp's
// event API, whose scanner was 5.9x slower on the corpus (measured in the same run, best of 20:
// 38.4 ms vs 6.5 ms for the 59 corpus .body/.yaml files) and the largest single cost of a
// bodycheck run. A DOM is not built first: a node reached through an alias must keep its use site
// (toolchain.md §3), and the expansion and depth budgets are applied while the events arrive.

#include "yaml/syntax_words.h"
#include "yaml/yaml_node.h"

#include <bodyfmt/rules.h>

#include <yaml.h>

#include <algorithm>
#include <exception>
#include <limits>
#include <new>
#include <unordered_map>
#include <unordered_set>

namespace bodyfmt::yaml {
namespace {

// Stops the event loop once a fatal diagnostic has been queued.
struct ParseAborted {};

// libyaml's parser keeps its own state stack and has no nesting limit, but readers of the tree
// recurse; this ceiling holds whatever ParseOptions::max_depth a caller asks for (yaml-cpp,
// the previous parser, had the same recursion guard of 500 levels).
constexpr std::size_t kNestingCeiling = 500;

bool is_blank_or_break(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool is_flow_indicator(char c) { return c == ',' || c == '[' || c == ']' || c == '{' || c == '}'; }

// Where an anchor or tag name written at `pos` ends: at a blank or a flow indicator.
std::size_t name_end(std::string_view text, std::size_t pos) {
  while (pos < text.size() && !is_blank_or_break(text[pos]) && !is_flow_indicator(text[pos])) ++pos;
  return pos;
}

std::size_t saturating_add(std::size_t a, std::size_t b) {
  return a > std::numeric_limits<std::size_t>::max() - b ? std::numeric_limits<std::size_t>::max() : a + b;
}

// A node's properties as written: its mark points at its first property (`&a`, `!tag`).
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

// Owns one libyaml event; the library allocates its strings. Not zeroed here:
// yaml_parser_parse clears it first, and zeroing its 104 bytes with `rep stos` on every event
// was 1.7 % of loading a 100k-link model.
struct Event {
  yaml_event_t event;
  bool owned = false;
  ~Event() {
    if (owned) yaml_event_delete(&event);
  }
};

struct Parser {
  yaml_parser_t parser{};
  bool initialized = false;
  ~Parser() {
    if (initialized) yaml_parser_delete(&parser);
  }
};

class TreeBuilder {
 public:
  TreeBuilder(std::string_view text, const std::string& file, const ParseOptions& options, Document& document)
      : text_(text), file_(file), options_(options), document_(document) {
    // libyaml skips a UTF-8 byte order mark without counting it in its marks.
    bom_size_ = text_.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
    ascii_ = std::none_of(text_.begin() + bom_size_, text_.end(),
                          [](char c) { return static_cast<unsigned char>(c) >= 0x80; });
  }

  std::vector<Diagnostic>& diagnostics() { return diagnostics_; }
  bool failed() const { return failed_; }

  /// Reads the first document. Returns its root, or an empty ref when the text holds none.
  /// Throws ParseAborted after a fatal diagnostic.
  NodeRef run() {
    Parser parser;
    if (yaml_parser_initialize(&parser.parser) == 0) throw std::bad_alloc();
    parser.initialized = true;
    yaml_parser_set_input_string(&parser.parser, reinterpret_cast<const unsigned char*>(text_.data()), text_.size());
    for (;;) {
      Event event;
      if (yaml_parser_parse(&parser.parser, &event.event) == 0) syntax_error(parser.parser);
      event.owned = true;
      const yaml_event_t& e = event.event;
      // UTF-16 input is transcoded by libyaml: its marks then say nothing about `text_`'s bytes.
      if (e.type == YAML_STREAM_START_EVENT) utf8_ = e.data.stream_start.encoding == YAML_UTF8_ENCODING;
      switch (e.type) {
        case YAML_SCALAR_EVENT: on_scalar(e); break;
        case YAML_ALIAS_EVENT: on_alias(e); break;
        case YAML_SEQUENCE_START_EVENT: {
          const auto& start = e.data.sequence_start;
          // A sequence with an anchor or a tag stays whole: an alias may use all of it.
          const bool streamable = start.anchor == nullptr && start.tag == nullptr;
          begin_collection(begin_node(NodeKind::kSequence, e.start_mark, start.anchor, start.tag), streamable);
          break;
        }
        case YAML_MAPPING_START_EVENT:
          begin_collection(
              begin_node(NodeKind::kMapping, e.start_mark, e.data.mapping_start.anchor, e.data.mapping_start.tag),
              false);
          break;
        case YAML_SEQUENCE_END_EVENT:
        case YAML_MAPPING_END_EVENT: end_collection(); break;
        // Only the first document is used (body-format-spec §1.8); later ones are not scanned.
        case YAML_DOCUMENT_END_EVENT:
        case YAML_STREAM_END_EVENT: return root_;
        default: break;  // stream and document starts carry nothing the tree needs
      }
    }
  }

  SourceLocation location(const yaml_mark_t& mark) {
    // libyaml marks are 0-based and count characters; columns here count bytes, as editors
    // and the rest of the toolchain do, so a line holding multi-byte text is measured again.
    int column = static_cast<int>(mark.column) + 1;
    if (!ascii_ && utf8_ && mark.column <= mark.index) {
      column = static_cast<int>(byte_offset(mark.index) - byte_offset(mark.index - mark.column)) + 1;
    }
    return SourceLocation{file_, static_cast<int>(mark.line) + 1, column};
  }

  void report(std::string_view rule_id, SourceLocation location, std::string message, std::string fix_hint = {}) {
    diagnostics_.push_back(make_diagnostic(rule_id, std::move(location), std::move(message), std::move(fix_hint)));
    if (diagnostics_.back().severity == Severity::kFatal) failed_ = true;
  }

 private:
  struct MergeSlot {
    std::size_t position = 0;  // number of local entries written before the `<<`
    std::vector<NodeRef> sources;
  };
  enum class KeyState { kNormal, kMerge, kSkip };
  // A mapping key as read: a plain scalar straight from its event, or any node through a ref.
  struct Key {
    std::string_view text;
    SourceLocation location;
    TextSpan span;
    const Node* complex = nullptr;  // a collection written as a key
  };
  // An open collection. Its children wait on the builder's shared stacks from `first_child` on
  // and move to the arena, in one piece, when it closes.
  struct Frame {
    Node* node = nullptr;
    bool mapping = false;            // node->is_mapping(), asked for every event without a load of the node
    bool is_key = false;             // the collection itself is a (complex) mapping key
    std::size_t count_at_start = 0;  // expanded_count_ before this collection was opened
    std::size_t first_child = 0;     // index into items_ or entries_
    // Mapping state.
    bool expecting_key = true;
    KeyState key_state = KeyState::kNormal;
    Key key;
    // Built once a mapping is large enough that scanning its keys would be quadratic.
    std::unique_ptr<std::unordered_map<std::string_view, std::size_t>> key_index;
    std::vector<MergeSlot> merges;
    // Items taken by ParseOptions::stream: no longer children, still part of the sizes.
    std::size_t streamed_size = 0;
    int streamed_depth = 0;
  };

  // The byte offset in `text_` of libyaml's character index (which does not count the BOM).
  std::size_t byte_offset(std::size_t index) {
    if (!utf8_) return text_.size();  // the text scans then find nothing
    if (ascii_) return std::min(index + bom_size_, text_.size());
    if (char_starts_.empty()) {
      for (std::size_t i = bom_size_; i < text_.size(); ++i) {
        if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80) char_starts_.push_back(i);
      }
      char_starts_.push_back(text_.size());
    }
    return index < char_starts_.size() ? char_starts_[index] : text_.size();
  }
  std::size_t offset(const yaml_mark_t& mark) { return byte_offset(mark.index); }

  [[noreturn]] void syntax_error(const yaml_parser_t& parser) {
    if (parser.error == YAML_MEMORY_ERROR) throw std::bad_alloc();
    std::string message = parser.problem != nullptr ? parser.problem : "invalid YAML";
    SourceLocation where;
    if (parser.error == YAML_READER_ERROR) {
      // Encoding errors carry a byte offset into the raw input instead of a mark.
      std::size_t at = std::min(parser.problem_offset, text_.size());
      std::size_t line_start = text_.rfind('\n', at == 0 ? 0 : at - 1);
      line_start = line_start == std::string_view::npos || at == 0 ? 0 : line_start + 1;
      int line = 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + at, '\n'));
      where = SourceLocation{file_, line, static_cast<int>(at - line_start) + 1};
    } else {
      where = location(parser.problem_mark);
      if (parser.context != nullptr) {
        SourceLocation context = location(parser.context_mark);
        message += " (" + std::string(parser.context) + " at line " + std::to_string(context.line) + ", column " +
                   std::to_string(context.column) + ")";
      }
    }
    // The user's terms first (a tab, a line indented unlike its neighbours); libyaml's words,
    // which name the parser's state, stay as the note.
    if (parser.error != YAML_READER_ERROR && utf8_) {
      // `type: RigidBody:` (a typo of Choreonoid's own tutorial): libyaml stops at the colon.
      if (parser.problem && std::string_view(parser.problem) == "mapping values are not allowed in this context") {
        if (std::optional<SyntaxWords> words = colon_in_value(text_, where.line, where.column)) {
          Diagnostic d = make_diagnostic("yaml-syntax", SourceLocation{file_, words->line, words->column},
                                         std::move(words->message), words->hint + " (libyaml: " + message + ")");
          if (words->edit) {
            // Unsafe: the file does not load as it is, so no model stays the same.
            FixIt fix;
            fix.file = file_;
            fix.begin = words->edit->begin;
            fix.end = words->edit->end;
            fix.line = words->line;
            fix.column = words->column;
            fix.original = std::string(text_.substr(fix.begin, fix.end - fix.begin));
            fix.replacement = words->edit->replacement;
            fix.safety = FixSafety::kUnsafe;
            d.fixes.push_back(std::move(fix));
          }
          diagnostics_.push_back(std::move(d));
          failed_ = true;
          throw ParseAborted{};
        }
      }
      if (std::optional<SyntaxWords> words = syntax_in_words(text_, where.line)) {
        report("yaml-syntax", SourceLocation{file_, words->line, words->column}, std::move(words->message),
               "libyaml: " + message);
        throw ParseAborted{};
      }
    }
    report("yaml-syntax", std::move(where), std::move(message));
    throw ParseAborted{};
  }

  void on_scalar(const yaml_event_t& e) {
    const auto& scalar = e.data.scalar;
    const std::string_view value(reinterpret_cast<const char*>(scalar.value), scalar.length);
    const bool plain = scalar.style == YAML_PLAIN_SCALAR_STYLE;
    if (in_key_position() && scalar.anchor == nullptr) {
      // A key is read once, into its mapping entry: it needs no node of its own (a key with an
      // anchor does, since an alias may use it as a value).
      const SourceLocation where = location(e.start_mark);
      Key key;
      key.text = document_.store(value);
      key.location = where;
      key.span = scalar_span(value, where, e);
      accept_key(frames_.back(), key);
      frames_.back().expecting_key = false;
      return;
    }
    Node* node = begin_node(NodeKind::kScalar, e.start_mark, scalar.anchor, scalar.tag);
    node->set_scalar(document_.store(value));
    node->plain = plain;
    node->span = scalar_span(value, node->location, e);
    // `key:` with nothing after it: the empty value has no text of its own; it is reported at
    // its key rather than at wherever libyaml's scanner stood.
    if (node->plain && node->scalar().empty() && scalar.anchor == nullptr && scalar.tag == nullptr &&
        !frames_.empty() && frames_.back().mapping && !frames_.back().expecting_key) {
      node->location = frames_.back().key.location;
    }
    finish_scalar(node);
  }

  void on_alias(const yaml_event_t& e) {
    const std::string name(reinterpret_cast<const char*>(e.data.alias.anchor));
    const Node* target = nullptr;
    if (auto it = local_anchors_.find(name); it != local_anchors_.end()) {
      target = it->second;
    } else if (options_.imported_anchors != nullptr) {
      // A YAML resource sees the main body file's anchors (body-format-spec §9.3); local ones
      // take priority. An imported node still under construction cannot be used.
      auto imported = options_.imported_anchors->find(name);
      if (imported != options_.imported_anchors->end() && imported->second->expanded_size != 0) {
        target = imported->second;
      }
    }
    if (target == nullptr) {
      // body-format-spec §1.4: Choreonoid refuses the file (Anchor is not defined).
      report("yaml-undefined-alias", location(e.start_mark),
             "alias \"*" + name + "\" refers to an anchor that is not defined before it",
             "define the anchor (&" + name + ") before its first use");
      failed_ = true;
      throw ParseAborted{};
    }
    add_alias(target, name, e.start_mark);
  }

  // Where the scalar's value is written verbatim, for fix-its: after its properties, inside its
  // quotes, on its first line, and only when the text equals the value (no escapes, no folding).
  TextSpan scalar_span(std::string_view value, const SourceLocation& where, const yaml_event_t& e) {
    const yaml_mark_t& start = e.start_mark;
    const yaml_mark_t& end = e.end_mark;
    const yaml_scalar_style_t style = e.data.scalar.style;
    const bool has_properties = e.data.scalar.anchor != nullptr || e.data.scalar.tag != nullptr;
    TextSpan span;
    if (!utf8_ || value.empty()) return span;
    const bool quoted = style == YAML_SINGLE_QUOTED_SCALAR_STYLE || style == YAML_DOUBLE_QUOTED_SCALAR_STYLE;
    if (style != YAML_PLAIN_SCALAR_STYLE && !quoted) return span;
    const std::size_t first = offset(start);
    // The mark is at the first property (`&a`, `!tag`) when there are any, else at the value.
    std::size_t begin = has_properties ? scan_node_text(text_, first).content : first;
    std::size_t stop = offset(end);
    if (quoted) {
      ++begin;
      if (stop == 0) return span;
      --stop;
    }
    if (begin > stop || stop > text_.size() || text_.substr(begin, stop - begin) != value) return span;
    if (text_.substr(first, begin - first).find('\n') != std::string_view::npos) return span;
    if (stop >= TextSpan::npos) return span;  // past 4 GiB: not editable in place
    span.begin = static_cast<std::uint32_t>(begin);
    span.end = static_cast<std::uint32_t>(stop);
    span.column = where.column + static_cast<int>(begin - first);
    return span;
  }

  bool in_key_position() const { return !frames_.empty() && frames_.back().mapping && frames_.back().expecting_key; }

  Node* begin_node(NodeKind kind, const yaml_mark_t& mark, const yaml_char_t* anchor, const yaml_char_t* tag) {
    Node* node = document_.make_node();
    node->kind = kind;
    node->location = location(mark);
    // libyaml resolves `!!str` to `tag:yaml.org,2002:str`; the tag is kept as written, so it is
    // read back from the text, where the node's mark points at its first property.
    if (tag != nullptr) document_.set_tag(node, scan_node_text(text_, offset(mark)).tag);
    if (anchor != nullptr) define_anchor(node, reinterpret_cast<const char*>(anchor));
    if (!in_key_position()) add_to_budget(1, node->location, false);
    return node;
  }

  void define_anchor(Node* node, const std::string& name) {
    ++anchors_defined_;
    local_anchors_[name] = node;  // a later alias sees the newest definition
    auto [it, inserted] = document_.anchors.emplace(name, node);
    if (!inserted) {
      // body-format-spec §1.4: Choreonoid rejects a duplicated anchor, stricter than YAML 1.2.
      report("yaml-anchor-redefined", node->location,
             "anchor \"" + name + "\" is already defined at line " + std::to_string(it->second->location.line),
             "give each anchor a unique name");
      failed_ = true;
    }
  }

  void add_to_budget(std::size_t nodes, const SourceLocation& where, bool via_alias) {
    expanded_count_ = saturating_add(expanded_count_, nodes);
    if (expanded_count_ <= options_.max_expanded_nodes) return;
    std::string limit = std::to_string(options_.max_expanded_nodes);
    report("yaml-alias-expansion", where,
           via_alias
               ? "expanding this alias makes the document larger than the limit of " + limit + " nodes (alias bomb?)"
               : "the document has more than the limit of " + limit + " nodes",
           "if the file is legitimate, raise the limit (--max-yaml-nodes, LoadOptions::max_expanded_yaml_nodes)");
    throw ParseAborted{};
  }

  void check_depth(int depth, const SourceLocation& where) {
    if (depth <= options_.max_depth) return;
    report("yaml-depth", where,
           "nesting is deeper than the limit of " + std::to_string(options_.max_depth) +
               " levels (counted through aliases)",
           "if the file is legitimate, raise the limit (ParseOptions::max_depth)");
    throw ParseAborted{};
  }

  void add_alias(const Node* target, const std::string& name, const yaml_mark_t& mark) {
    SourceLocation site = location(mark);
    if (target->expanded_size == 0) {
      // `&a [*a]`: the anchor is registered before its content, so this would be a cycle.
      report("yaml-recursive-alias", site,
             "alias \"*" + name + "\" refers to a node that contains it (defined at line " +
                 std::to_string(target->location.line) + ")");
      throw ParseAborted{};
    }
    if (!in_key_position()) add_to_budget(target->expanded_size, site, true);
    check_depth(static_cast<int>(frames_.size()) + target->expanded_depth, site);
    deliver(NodeRef{target, document_.store(site), nullptr});
  }

  void finish_scalar(Node* node) {
    node->expanded_size = 1;
    node->expanded_depth = 0;
    deliver(NodeRef{node, nullptr, nullptr});
  }

  void begin_collection(Node* node, bool streamable) {
    const bool streamed = streamable && offer_to_stream(*node);
    Frame frame;
    frame.node = node;
    frame.mapping = node->is_mapping();
    frame.is_key = in_key_position();
    frame.count_at_start = expanded_count_ - (frame.is_key ? 0 : 1);
    frame.first_child = node->is_mapping() ? entries_.size() : items_.size();
    frames_.push_back(std::move(frame));
    check_depth(static_cast<int>(frames_.size()), node->location);
    if (frames_.size() > kNestingCeiling) {
      report("yaml-depth", node->location,
             "nesting is deeper than the parser's limit of " + std::to_string(kNestingCeiling) + " levels");
      throw ParseAborted{};
    }
    if (streamed) {
      stream_frame_ = frames_.size();
      start_item();
    }
  }

  // Whether ParseOptions::stream takes the items of `sequence`, which is about to open: it
  // must be the value of the stream's key in the top-level mapping.
  bool offer_to_stream(const Node& sequence) {
    if (options_.stream == nullptr || stream_frame_ != 0 || !sequence.is_sequence() || frames_.size() != 1)
      return false;
    const Frame& root = frames_.front();
    if (!root.node->is_mapping() || root.is_key || root.expecting_key || root.key_state != KeyState::kNormal ||
        root.key.text != options_.stream->key()) {
      return false;
    }
    Node head;
    head.kind = NodeKind::kMapping;
    head.location = root.node->location;
    head.set_entries(Children<MapEntry>(entries_.data() + root.first_child, entries_.size() - root.first_child));
    return options_.stream->begin(head, sequence);
  }

  void start_item() {
    item_start_ = document_.mark();
    anchors_at_item_ = anchors_defined_;
    tags_at_item_ = document_.tag_count();
  }

  // A finished item of the streamed sequence: the consumer's, or the sequence's when declined.
  void stream_item(const NodeRef& item) {
    Frame& frame = frames_.back();
    if (!options_.stream->take(item)) {
      items_.push_back(item);
    } else {
      frame.streamed_size = saturating_add(frame.streamed_size, item->expanded_size);
      frame.streamed_depth = std::max(frame.streamed_depth, item->expanded_depth);
      // An anchor or a tag defined inside may be used later: then the item's memory stays.
      if (anchors_defined_ == anchors_at_item_ && document_.tag_count() == tags_at_item_) document_.rewind(item_start_);
    }
    start_item();
  }

  void end_collection() {
    Frame frame = std::move(frames_.back());
    frames_.pop_back();
    Node* node = frame.node;
    if (node->is_mapping() && !frame.merges.empty()) apply_merges(frame);
    if (frames_.size() + 1 == stream_frame_) stream_frame_ = 0;
    std::size_t size = saturating_add(1, frame.streamed_size);
    int depth = frame.streamed_depth;
    auto measure = [&](const NodeRef& child) {
      size = saturating_add(size, child->expanded_size);
      depth = std::max(depth, child->expanded_depth);
    };
    if (node->is_mapping()) {
      for (std::size_t i = frame.first_child; i < entries_.size(); ++i) measure(entries_[i].value);
      node->set_entries(document_.store(entries_.data() + frame.first_child, entries_.size() - frame.first_child));
      entries_.resize(frame.first_child);
      first_lines_.resize(frame.first_child);
    } else {
      for (std::size_t i = frame.first_child; i < items_.size(); ++i) measure(items_[i]);
      node->set_items(document_.store(items_.data() + frame.first_child, items_.size() - frame.first_child));
      items_.resize(frame.first_child);
    }
    node->expanded_size = size;
    node->expanded_depth = depth + 1;
    // The running count was provisional (merge sources and overwritten duplicates counted in
    // full); replace it by the exact size now that the collection is final.
    expanded_count_ = frame.count_at_start;
    if (!frame.is_key) add_to_budget(size, node->location, false);
    deliver(NodeRef{node, nullptr, nullptr});
  }

  void deliver(const NodeRef& ref) {
    if (frames_.empty()) {
      root_ = ref;
      return;
    }
    if (frames_.size() == stream_frame_) {
      stream_item(ref);
      return;
    }
    Frame& frame = frames_.back();
    if (!frame.mapping) {
      items_.push_back(ref);
    } else if (frame.expecting_key) {
      Key key;
      key.location = ref.use_site();
      if (ref->is_scalar()) {
        key.text = ref->scalar();
        key.span = ref.alias_site != nullptr ? TextSpan{} : ref->span;
      } else {
        key.complex = ref.node;
      }
      accept_key(frame, key);
      frame.expecting_key = false;
    } else {
      accept_value(frame, ref);
      frame.expecting_key = true;
    }
  }

  void accept_key(Frame& frame, const Key& key) {
    frame.key = key;
    if (key.complex != nullptr) {
      report(
          "yaml-complex-key", key.location,
          "a mapping key must be a scalar, not a " + std::string(key.complex->is_mapping() ? "mapping" : "sequence"));
      frame.key_state = KeyState::kSkip;
    } else if (key.text.empty()) {
      // body-format-spec §1.8: Choreonoid reports "empty key".
      report("yaml-empty-key", key.location, "empty mapping key");
      frame.key_state = KeyState::kSkip;
    } else {
      // body-format-spec §1.5: Choreonoid compares the key text, whatever its quoting.
      frame.key_state = key.text == "<<" ? KeyState::kMerge : KeyState::kNormal;
    }
  }

  // The entry of `frame`'s mapping with this key, or npos.
  std::size_t find_local(Frame& frame, std::string_view key) {
    constexpr std::size_t kScanLimit = 16;
    const std::size_t count = entries_.size() - frame.first_child;
    if (count <= kScanLimit) {
      // Keys are never empty here; the first byte settles most mismatches without memcmp.
      for (std::size_t i = frame.first_child; i < entries_.size(); ++i) {
        const std::string_view other = entries_[i].key;
        if (other.size() == key.size() && other[0] == key[0] && other == key) return i;
      }
      return std::string_view::npos;
    }
    if (!frame.key_index) {
      frame.key_index = std::make_unique<std::unordered_map<std::string_view, std::size_t>>();
      for (std::size_t i = frame.first_child; i < entries_.size(); ++i) frame.key_index->emplace(entries_[i].key, i);
    }
    auto it = frame.key_index->find(key);
    return it == frame.key_index->end() ? std::string_view::npos : it->second;
  }

  void accept_value(Frame& frame, const NodeRef& value) {
    if (frame.key_state == KeyState::kSkip) return;
    if (frame.key_state == KeyState::kMerge) {
      add_merge(frame, value);
      return;
    }
    const Key& key = frame.key;
    const std::size_t existing = find_local(frame, key.text);
    if (existing == std::string_view::npos) {
      if (frame.key_index) frame.key_index->emplace(key.text, entries_.size());
      entries_.push_back(MapEntry{key.text, key.location, key.span, false, value});
      first_lines_.push_back(key.location.line);
      return;
    }
    // body-format-spec §1.6: the last one wins (WAREC1's `type: Collision` then `type: Group`).
    report("yaml-duplicate-key", key.location,
           "duplicate key \"" + std::string(key.text) + "\" (first at line " + std::to_string(first_lines_[existing]) +
               "); the last value wins",
           "remove one of the two entries");
    MapEntry& entry = entries_[existing];
    entry.key_location = key.location;
    entry.key_span = key.span;
    entry.value = value;
  }

  // body-format-spec §1.5: the value of `<<` is a mapping or a sequence of mappings.
  void add_merge(Frame& frame, const NodeRef& value) {
    MergeSlot slot;
    slot.position = entries_.size() - frame.first_child;
    if (value->is_mapping()) {
      slot.sources.push_back(value);
    } else if (value->is_sequence()) {
      for (const NodeRef& item : value->items()) {
        if (item->is_mapping()) {
          slot.sources.push_back(item);
        } else {
          report("yaml-merge-invalid", item.use_site(), "an element to merge by the \"<<\" key must be a mapping");
        }
      }
    } else {
      report("yaml-merge-invalid", value.use_site(),
             "a value to merge by the \"<<\" key must be a mapping or a sequence of mappings");
    }
    frame.merges.push_back(std::move(slot));
  }

  // Local keys win wherever they are written; among merge sources the first one wins. Merged
  // entries take the place of the `<<` entry, which is dropped. Sources are finished nodes, so
  // their own merges are already applied (nested merges need no recursion).
  void apply_merges(Frame& frame) {
    std::vector<MapEntry> locals(entries_.begin() + static_cast<std::ptrdiff_t>(frame.first_child), entries_.end());
    std::unordered_set<std::string_view> present;
    for (const MapEntry& entry : locals) present.insert(entry.key);
    std::vector<MapEntry> merged;
    std::size_t next_local = 0;
    for (const MergeSlot& slot : frame.merges) {
      while (next_local < slot.position) merged.push_back(locals[next_local++]);
      for (const NodeRef& source : slot.sources) {
        for (const MapEntry& entry : source->entries()) {
          if (!present.insert(entry.key).second) continue;
          merged.push_back(MapEntry{entry.key, entry.key_location, entry.key_span, true, entry.value});
        }
      }
    }
    while (next_local < locals.size()) merged.push_back(locals[next_local++]);
    entries_.resize(frame.first_child);
    entries_.insert(entries_.end(), merged.begin(), merged.end());
    first_lines_.resize(entries_.size());
  }

  std::string_view text_;
  std::size_t bom_size_ = 0;
  bool ascii_ = true;  // no multi-byte character: libyaml's character counts are byte counts
  bool utf8_ = true;
  std::vector<std::size_t> char_starts_;  // byte offset of each character, built on demand
  const FileName file_;                   // interned once: every node's location names it
  const ParseOptions& options_;
  Document& document_;

  std::vector<Diagnostic> diagnostics_;
  bool failed_ = false;
  NodeRef root_;
  std::vector<Frame> frames_;
  std::vector<NodeRef> items_;     // children of the open sequences, innermost last
  std::vector<MapEntry> entries_;  // entries of the open mappings, innermost last
  std::vector<int> first_lines_;   // per entries_ element: the line its key was first written on
  std::unordered_map<std::string, const Node*> local_anchors_;
  std::size_t expanded_count_ = 0;  // nodes seen so far, aliases expanded (provisional)
  std::size_t anchors_defined_ = 0;
  // The streamed sequence (ParseOptions::stream): its depth in frames_ (0 = none), and the
  // state when its current item began.
  std::size_t stream_frame_ = 0;
  Arena::Mark item_start_;
  std::size_t anchors_at_item_ = 0;
  std::size_t tags_at_item_ = 0;
};

}  // namespace

namespace {

bool is_out_of_memory(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::bad_alloc&) {
    return true;
  } catch (...) {
    return false;
  }
}

/// The offset of a NUL byte near the start of `text`, which no YAML text in UTF-8 holds (UTF-16
/// and UTF-32 start with a byte-order mark, and libyaml transcodes them), or npos.
std::size_t binary_marker(std::string_view text) {
  const bool utf16_or_32 =
      text.size() >= 2 && ((text[0] == '\xFF' && text[1] == '\xFE') || (text[0] == '\xFE' && text[1] == '\xFF') ||
                           (text.size() >= 4 && text.substr(0, 4) == std::string_view("\0\0\xFE\xFF", 4)));
  if (utf16_or_32) return std::string_view::npos;
  return text.substr(0, 8192).find('\0');
}

}  // namespace

std::unique_ptr<Document> parse_yaml(std::string_view text, const std::string& file_name, const ParseOptions& options,
                                     DiagnosticSink& sink) {
  if (const std::size_t nul = binary_marker(text); nul != std::string_view::npos) {
    // One line, without an excerpt: the "source line" of a binary file is noise.
    sink.report(make_diagnostic("yaml-syntax", SourceLocation{file_name, 0, 0},
                                "this is a binary file, not YAML text (a NUL byte at byte " + std::to_string(nul) +
                                    "); a .body model is a YAML text file"));
    return nullptr;
  }
  if (text.size() >= TextSpan::npos) {
    // Node sizes and text spans are 32-bit; LoadOptions::max_file_bytes is far below this.
    sink.report(
        make_diagnostic("yaml-syntax", SourceLocation{file_name, 0, 0},
                        "cannot read a YAML text of 4 GiB or more (" + std::to_string(text.size()) + " bytes)"));
    return nullptr;
  }
  auto document = std::make_unique<Document>();
  document->file = file_name;
  std::vector<Diagnostic> diagnostics;
  try {
    TreeBuilder builder(text, file_name, options, *document);
    bool usable = true;
    try {
      NodeRef root = builder.run();
      if (!root) {
        Node* empty = document->make_node();
        empty->location = SourceLocation{file_name, 1, 1};
        empty->expanded_size = 1;
        root = NodeRef{empty, nullptr, nullptr};
      }
      document->root = std::move(root);
      document->expanded_node_count = document->root->expanded_size;
    } catch (const ParseAborted&) {
      usable = false;
    }
    diagnostics = std::move(builder.diagnostics());
    if (!usable || builder.failed()) document.reset();
  } catch (...) {
    // Never throw across the API (style.md §2.4), except what a SequenceConsumer threw: that is
    // the caller's own (the loader reports its broken invariants as internal errors).
    if (options.stream != nullptr && !is_out_of_memory(std::current_exception())) throw;
    document.reset();
    diagnostics.clear();
    diagnostics.push_back(
        make_diagnostic("yaml-syntax", SourceLocation{file_name, 0, 0}, "cannot read the YAML text (out of memory?)"));
  }
  for (Diagnostic& diagnostic : diagnostics) sink.report(std::move(diagnostic));
  return document;
}

}  // namespace bodyfmt::yaml
