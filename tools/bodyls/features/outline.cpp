#include "outline.h"

#include <algorithm>
#include <cctype>

namespace bodyfmt::lsp {

TextIndex::TextIndex(std::string_view text) : size_(text.size()) {
  line_starts_.push_back(0);
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') line_starts_.push_back(i + 1);
}

TextPoint TextIndex::point(std::size_t offset) const {
  offset = std::min(offset, size_);
  const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  const auto line = static_cast<std::size_t>(it - line_starts_.begin()) - 1;
  return {static_cast<int>(line) + 1, static_cast<int>(offset - line_starts_[line]) + 1};
}

std::size_t TextIndex::offset(TextPoint at) const {
  if (at.line < 1) return 0;
  const auto line = static_cast<std::size_t>(at.line) - 1;
  if (line >= line_starts_.size()) return size_;
  const std::size_t begin = line_starts_[line];
  // The line's end is before its newline (and its carriage return).
  std::size_t end = line + 1 < line_starts_.size() ? line_starts_[line + 1] - 1 : size_;
  const std::size_t column = at.column < 1 ? 0 : static_cast<std::size_t>(at.column) - 1;
  return std::min(begin + column, end);
}

namespace {

constexpr int kMaxDepth = 100;

bool is_space(char c) { return c == ' ' || c == '\t'; }
bool is_break(char c) { return c == '\n' || c == '\r'; }

}  // namespace

/// Recursive descent over the text with an explicit depth limit; every loop advances or stops.
class OutlineParser {
 public:
  OutlineParser(Outline& out, std::string_view text) : out_(out), t_(text) {}

  void run() {
    skip_document_start();
    out_.root_ = parse_block(-1, -1, 0);
  }

 private:
  Outline& out_;
  std::string_view t_;
  std::size_t pos_ = 0;

  char at(std::size_t i) const { return i < t_.size() ? t_[i] : '\0'; }
  bool eof() const { return pos_ >= t_.size(); }
  std::size_t line_start(std::size_t p) const {
    while (p > 0 && t_[p - 1] != '\n') --p;
    return p;
  }
  int column(std::size_t p) const { return static_cast<int>(p - line_start(p)); }
  /// The column of the line's first character other than a space.
  int indent_of_line(std::size_t p) const {
    std::size_t s = line_start(p), i = s;
    while (i < t_.size() && t_[i] == ' ') ++i;
    return static_cast<int>(i - s);
  }
  void skip_spaces() {
    while (!eof() && is_space(t_[pos_])) ++pos_;
  }
  bool at_line_end() const { return eof() || is_break(t_[pos_]) || (t_[pos_] == '#'); }
  void skip_to_line_end() {
    while (!eof() && t_[pos_] != '\n') ++pos_;
  }
  /// Past spaces, comments and line breaks to the next character that means something.
  void skip_blank() {
    for (;;) {
      skip_spaces();
      if (eof()) return;
      if (t_[pos_] == '#') skip_to_line_end();
      if (!eof() && is_break(t_[pos_])) {
        ++pos_;
        continue;
      }
      return;
    }
  }
  void skip_document_start() {
    skip_blank();
    if (t_.substr(pos_, 3) == "---" && (is_space(at(pos_ + 3)) || is_break(at(pos_ + 3)) || pos_ + 3 >= t_.size()))
      pos_ += 3;
  }

  int add(OutlineNode node) {
    out_.nodes_.push_back(std::move(node));
    return static_cast<int>(out_.nodes_.size()) - 1;
  }
  OutlineNode& n(int i) { return out_.nodes_[static_cast<std::size_t>(i)]; }
  int null_at(int parent, std::size_t p) {
    OutlineNode node;
    node.begin = node.end = p;
    node.parent = parent;
    return add(std::move(node));
  }

  /// A key at pos_ in block context: a plain or quoted word followed by ':' and a space or
  /// the line's end. Gives the key's end (before ':') and the position after the ':'.
  bool key_ahead(std::size_t& key_end, std::size_t& after) const {
    std::size_t i = pos_;
    const char c = at(i);
    if (c == '"' || c == '\'') {
      ++i;
      while (i < t_.size() && t_[i] != c && !is_break(t_[i])) ++i;
      if (at(i) != c) return false;
      ++i;
      key_end = i;
      while (is_space(at(i))) ++i;
      if (at(i) != ':') return false;
    } else {
      if (c == '-' || c == '[' || c == '{' || c == '*' || c == '&' || c == '!' || c == '|' || c == '>' || c == '#')
        if (!(c == '-' && !is_space(at(i + 1)) && !is_break(at(i + 1)) && i + 1 < t_.size())) return false;
      while (i < t_.size() && !is_break(t_[i])) {
        if (t_[i] == ':' && (i + 1 >= t_.size() || is_space(t_[i + 1]) || is_break(t_[i + 1]))) break;
        if (t_[i] == '#' && i > pos_ && is_space(t_[i - 1])) return false;
        ++i;
      }
      if (at(i) != ':') return false;
      key_end = i;
      while (key_end > pos_ && is_space(t_[key_end - 1])) --key_end;
    }
    after = i + 1;
    return true;
  }

  static std::string unquote(std::string_view s) {
    if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front())
      return std::string(s.substr(1, s.size() - 2));
    return std::string(s);
  }

  /// A word typed on a line of a block mapping without its ':' yet: an entry without value.
  bool partial_key_ahead(std::size_t& key_end) const {
    std::size_t i = pos_;
    while (i < t_.size() && (std::isalnum(static_cast<unsigned char>(t_[i])) || t_[i] == '_')) ++i;
    if (i == pos_) return false;
    std::size_t j = i;
    while (is_space(at(j))) ++j;
    if (j < t_.size() && !is_break(t_[j]) && t_[j] != '#') return false;
    key_end = i;
    return true;
  }

  /// Anchors and tags before a node: `&name`, `!tag`.
  void properties(OutlineNode& node) {
    for (;;) {
      if (at(pos_) == '&') {
        node.anchor_begin = pos_;
        ++pos_;
        const std::size_t name = pos_;
        while (!eof() && !is_space(t_[pos_]) && !is_break(t_[pos_]) && t_[pos_] != ',' && t_[pos_] != ']' &&
               t_[pos_] != '}')
          ++pos_;
        node.anchor = std::string(t_.substr(name, pos_ - name));
        node.anchor_end = pos_;
        skip_spaces();
      } else if (at(pos_) == '!') {
        while (!eof() && !is_space(t_[pos_]) && !is_break(t_[pos_])) ++pos_;
        skip_spaces();
      } else {
        return;
      }
    }
  }

  /// A node in block context: at pos_ or on a following line indented deeper than
  /// `block_indent` (the enclosing collection's column).
  int parse_block(int parent, int block_indent, int depth) {
    const std::size_t start = pos_;
    const std::size_t start_line = line_start(pos_);
    skip_blank();
    if (eof() || (line_start(pos_) != start_line && indent_of_line(pos_) <= block_indent)) {
      pos_ = start;
      return null_at(parent, start);
    }
    OutlineNode props;
    const std::size_t props_begin = pos_;
    properties(props);
    if (at_line_end() && !props.anchor.empty() && depth <= kMaxDepth) {
      // `key: &a` then the node on the next lines.
      skip_to_line_end();
      const int inner = parse_block(parent, block_indent, depth + 1);
      if (!props.anchor.empty() && n(inner).anchor.empty()) {
        n(inner).anchor = props.anchor;
        n(inner).anchor_begin = props.anchor_begin;
        n(inner).anchor_end = props.anchor_end;
        n(inner).begin = std::min(n(inner).begin, props_begin);
      }
      return inner;
    }
    int result = -1;
    if (depth > kMaxDepth) {
      OutlineNode node;
      node.kind = OutlineNode::kScalar;
      node.begin = pos_;
      skip_to_line_end();
      node.end = pos_;
      node.parent = parent;
      result = add(std::move(node));
    } else if (at(pos_) == '-' && (is_space(at(pos_ + 1)) || is_break(at(pos_ + 1)) || pos_ + 1 >= t_.size())) {
      result = parse_block_sequence(parent, depth);
    } else if (at(pos_) == '[' || at(pos_) == '{' || at(pos_) == '*' || at(pos_) == '|' || at(pos_) == '>') {
      if (at(pos_) == '|' || at(pos_) == '>')
        result = parse_block_scalar(parent, block_indent);
      else
        result = parse_flow(parent, block_indent, depth);
    } else {
      std::size_t key_end = 0, after = 0;
      if (key_ahead(key_end, after))
        result = parse_block_mapping(parent, depth);
      else
        result = parse_plain_line(parent);
    }
    if (!props.anchor.empty()) {
      n(result).anchor = props.anchor;
      n(result).anchor_begin = props.anchor_begin;
      n(result).anchor_end = props.anchor_end;
      n(result).begin = props_begin;
    }
    return result;
  }

  /// A scalar node at pos_; a quoted one is complete (it ends after its closing quote, or at the
  /// line's end while unclosed), a plain one's end is left to the caller's context.
  OutlineNode scalar_node(int parent) const {
    OutlineNode node;
    node.kind = OutlineNode::kScalar;
    node.parent = parent;
    node.begin = pos_;
    const char q = at(pos_);
    if (q == '"' || q == '\'') {
      std::size_t i = pos_ + 1;
      while (i < t_.size() && t_[i] != q && !is_break(t_[i])) i += (q == '"' && t_[i] == '\\') ? 2 : 1;
      i = std::min(i, t_.size());
      node.end = at(i) == q ? i + 1 : i;
      node.quoted = true;
    }
    return node;
  }

  int parse_plain_line(int parent) {
    OutlineNode node = scalar_node(parent);
    if (!node.quoted) {
      std::size_t i = pos_;
      while (i < t_.size() && !is_break(t_[i]) && !(t_[i] == '#' && i > pos_ && is_space(t_[i - 1]))) ++i;
      while (i > pos_ && is_space(t_[i - 1])) --i;
      node.end = i;
    }
    node.scalar = unquote(t_.substr(node.begin, node.end - node.begin));
    pos_ = node.end;
    skip_to_line_end();
    return add(std::move(node));
  }

  int parse_block_scalar(int parent, int block_indent) {
    OutlineNode node;
    node.kind = OutlineNode::kScalar;
    node.parent = parent;
    node.begin = pos_;
    skip_to_line_end();
    node.end = pos_;
    // Its lines: those indented deeper than the collection that holds it, and blank ones.
    while (!eof()) {
      std::size_t next = pos_ + 1;
      std::size_t i = next;
      while (i < t_.size() && t_[i] == ' ') ++i;
      const bool blank = i >= t_.size() || is_break(t_[i]);
      if (!blank && static_cast<int>(i - next) <= block_indent) break;
      pos_ = next;
      skip_to_line_end();
      if (!blank) node.end = pos_;
      if (next >= t_.size()) break;
    }
    return add(std::move(node));
  }

  /// The next line that means something, if its first character is at `indent` and
  /// `accept` says so; else pos_ stays where it was.
  template <typename Accept>
  bool next_line_at(int indent, Accept accept) {
    for (;;) {
      const std::size_t save = pos_;
      skip_to_line_end();
      skip_blank();
      if (eof()) {
        pos_ = save;
        return false;
      }
      const int col = column(pos_);
      if (col == indent && accept()) return true;
      if (col > indent) continue;  // a line indented deeper than it can be: skipped
      pos_ = save;
      return false;
    }
  }

  int parse_block_mapping(int parent, int depth) {
    OutlineNode node;
    node.kind = OutlineNode::kMapping;
    node.parent = parent;
    node.begin = pos_;
    node.indent = column(pos_);
    const int me = add(std::move(node));
    const int indent = n(me).indent;
    for (;;) {
      OutlineEntry entry;
      std::size_t key_end = 0, after = 0;
      entry.key_begin = pos_;
      if (key_ahead(key_end, after)) {
        entry.key_end = key_end;
        entry.key = unquote(t_.substr(pos_, key_end - pos_));
        pos_ = after;
        skip_spaces();
        if (at_line_end()) {
          // The value on the next lines: deeper, or a sequence at the key's own column.
          const std::size_t save = pos_;
          skip_to_line_end();
          skip_blank();
          const bool sequence_here =
              !eof() && column(pos_) == indent && at(pos_) == '-' && (is_space(at(pos_ + 1)) || is_break(at(pos_ + 1)));
          pos_ = save;
          if (sequence_here) {
            skip_to_line_end();
            skip_blank();
            entry.value = parse_block_sequence(me, depth + 1);
          } else {
            entry.value = parse_block(me, indent, depth + 1);
          }
        } else {
          entry.value = parse_block(me, indent, depth + 1);
        }
      } else if (partial_key_ahead(key_end)) {
        entry.key_end = key_end;
        entry.key = std::string(t_.substr(pos_, key_end - pos_));
        pos_ = key_end;
        entry.value = null_at(me, pos_);
      } else {
        // Not a key at the mapping's column: a stray line, skipped.
        entry.value = -1;
      }
      if (entry.value >= 0) {
        n(me).end = std::max(n(entry.value).end, entry.key_end);
        n(me).entries.push_back(std::move(entry));
      }
      const std::size_t before = pos_;
      if (!next_line_at(indent, [&] {
            return !(at(pos_) == '-' && (is_space(at(pos_ + 1)) || is_break(at(pos_ + 1)))) && at(pos_) != '#';
          }))
        break;
      if (pos_ <= before) break;
    }
    return me;
  }

  int parse_block_sequence(int parent, int depth) {
    OutlineNode node;
    node.kind = OutlineNode::kSequence;
    node.parent = parent;
    node.begin = pos_;
    node.indent = column(pos_);
    const int me = add(std::move(node));
    const int indent = n(me).indent;
    for (;;) {
      ++pos_;  // the '-'
      skip_spaces();
      const int item = parse_block(me, indent, depth + 1);
      n(me).items.push_back(item);
      n(me).end = std::max(n(me).end, std::max(n(item).end, n(me).begin + 1));
      const std::size_t before = pos_;
      if (!next_line_at(indent, [&] {
            return at(pos_) == '-' && (is_space(at(pos_ + 1)) || is_break(at(pos_ + 1)) || pos_ + 1 >= t_.size());
          }))
        break;
      if (pos_ <= before) break;
    }
    return me;
  }

  /// Past blanks inside a flow collection; false when the next line is indented no deeper
  /// than the block collection around it (the bracket was left open).
  bool skip_flow_blank(int block_indent) {
    for (;;) {
      skip_spaces();
      if (eof()) return false;
      if (t_[pos_] == '#') skip_to_line_end();
      if (!eof() && is_break(t_[pos_])) {
        const std::size_t save = pos_;
        ++pos_;
        skip_spaces();
        if (!eof() && !is_break(t_[pos_]) && t_[pos_] != '#' && column(pos_) <= block_indent) {
          pos_ = save;
          return false;
        }
        continue;
      }
      return !eof();
    }
  }

  int parse_flow_scalar(int parent) {
    OutlineNode node = scalar_node(parent);
    if (!node.quoted) {
      std::size_t i = pos_;
      while (i < t_.size() && !is_break(t_[i]) && t_[i] != ',' && t_[i] != ']' && t_[i] != '}' && t_[i] != '[' &&
             t_[i] != '{' && !(t_[i] == ':' && (is_space(at(i + 1)) || at(i + 1) == ',' || at(i + 1) == '}')) &&
             !(t_[i] == '#' && i > pos_ && is_space(t_[i - 1])))
        ++i;
      while (i > pos_ && is_space(t_[i - 1])) --i;
      node.end = i;
    }
    node.scalar = unquote(t_.substr(node.begin, node.end - node.begin));
    pos_ = node.end;
    return add(std::move(node));
  }

  int parse_alias(int parent) {
    OutlineNode node;
    node.kind = OutlineNode::kAlias;
    node.parent = parent;
    node.begin = pos_;
    ++pos_;
    while (!eof() && !is_space(t_[pos_]) && !is_break(t_[pos_]) && t_[pos_] != ',' && t_[pos_] != ']' &&
           t_[pos_] != '}')
      ++pos_;
    node.end = pos_;
    node.scalar = std::string(t_.substr(node.begin + 1, node.end - node.begin - 1));
    return add(std::move(node));
  }

  int parse_flow_node(int parent, int block_indent, int depth) {
    OutlineNode props;
    const std::size_t props_begin = pos_;
    properties(props);
    int result;
    if (depth > kMaxDepth)
      result = parse_flow_scalar(parent);
    else if (at(pos_) == '[' || at(pos_) == '{')
      result = parse_flow(parent, block_indent, depth + 1);
    else if (at(pos_) == '*')
      result = parse_alias(parent);
    else
      result = parse_flow_scalar(parent);
    if (!props.anchor.empty()) {
      n(result).anchor = props.anchor;
      n(result).anchor_begin = props.anchor_begin;
      n(result).anchor_end = props.anchor_end;
      n(result).begin = props_begin;
    }
    return result;
  }

  int parse_flow(int parent, int block_indent, int depth) {
    if (at(pos_) == '*') return parse_alias(parent);
    const bool mapping = at(pos_) == '{';
    const char close = mapping ? '}' : ']';
    OutlineNode node;
    node.kind = mapping ? OutlineNode::kMapping : OutlineNode::kSequence;
    node.parent = parent;
    node.begin = pos_;
    const int me = add(std::move(node));
    ++pos_;
    n(me).end = pos_;
    while (skip_flow_blank(block_indent)) {
      const std::size_t before = pos_;
      const char c = t_[pos_];
      if (c == close) {
        ++pos_;
        n(me).end = pos_;
        break;
      }
      if (c == ',') {
        ++pos_;
        n(me).end = pos_;
        continue;
      }
      if (c == ']' || c == '}') {  // the other bracket: stop here
        break;
      }
      if (mapping) {
        OutlineEntry entry;
        entry.key_begin = pos_;
        const int key = parse_flow_scalar(me);
        entry.key = n(key).scalar;
        entry.key_end = n(key).end;
        n(key).kind = OutlineNode::kNull;  // keys are entries, not nodes
        n(key).parent = -2;
        skip_spaces();
        if (at(pos_) == ':') {
          ++pos_;
          skip_spaces();
          if (at(pos_) == ',' || at(pos_) == close || at_line_end())
            entry.value = null_at(me, pos_);
          else
            entry.value = parse_flow_node(me, block_indent, depth);
        } else {
          entry.value = null_at(me, pos_);
        }
        n(me).end = std::max(pos_, n(entry.value).end);
        n(me).entries.push_back(std::move(entry));
      } else {
        const int item = parse_flow_node(me, block_indent, depth);
        skip_spaces();
        if (at(pos_) == ':') {  // `[a: b]`: a one-pair mapping; its value is skipped
          ++pos_;
          skip_spaces();
          if (at(pos_) != ',' && at(pos_) != close && !at_line_end()) parse_flow_node(me, block_indent, depth);
        }
        n(me).items.push_back(item);
        n(me).end = std::max(pos_, n(item).end);
      }
      if (pos_ <= before) ++pos_;  // never stand still on a character nothing reads
    }
    return me;
  }
};

Outline::Outline(std::string_view text) : text_(text) {
  nodes_.reserve(text.size() / 24 + 16);  // about one node per short line; saves most regrowth
  OutlineParser parser(*this, text);
  parser.run();
}

int Outline::node_at(std::size_t offset) const {
  int best = root_;
  std::size_t best_size = static_cast<std::size_t>(-1);
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const OutlineNode& node = nodes_[i];
    if (node.parent == -2) continue;
    if (node.begin <= offset && offset <= node.end && node.end - node.begin < best_size) {
      best = static_cast<int>(i);
      best_size = node.end - node.begin;
    }
  }
  return best;
}

const OutlineEntry* Outline::find(int map, std::string_view key) const {
  if (map < 0 || map >= static_cast<int>(nodes_.size())) return nullptr;
  for (const OutlineEntry& e : node(map).entries)
    if (e.key == key) return &e;
  return nullptr;
}

std::string Outline::scalar_of(int map, std::string_view key) const {
  const OutlineEntry* e = find(map, key);
  if (!e || e->value < 0 || node(e->value).kind != OutlineNode::kScalar) return {};
  return node(e->value).scalar;
}

const OutlineEntry* Outline::entry_of(int i) const {
  if (i < 0 || i >= static_cast<int>(nodes_.size())) return nullptr;
  const int parent = node(i).parent;
  if (parent < 0) return nullptr;
  for (const OutlineEntry& e : node(parent).entries)
    if (e.value == i) return &e;
  return nullptr;
}

}  // namespace bodyfmt::lsp
