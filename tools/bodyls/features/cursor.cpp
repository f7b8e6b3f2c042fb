#include "cursor.h"

namespace bodyfmt::lsp {

const OutlineEntry* holder_of(const Outline& o, int node, int& mapping) {
  mapping = -1;
  int current = node;
  for (int guard = 0; current >= 0 && guard < 1000; ++guard) {
    const int parent = o.node(current).parent;
    if (parent < 0) return nullptr;
    if (o.node(parent).kind == OutlineNode::kMapping) {
      mapping = parent;
      return o.entry_of(current);
    }
    if (o.node(parent).kind != OutlineNode::kSequence) return nullptr;
    current = parent;
  }
  return nullptr;
}

AtCursor locate(const Outline& o, std::size_t offset) {
  AtCursor at;
  const auto& nodes = o.nodes();
  for (std::size_t i = 0; i < nodes.size() && !at.key; ++i) {
    if (nodes[i].kind != OutlineNode::kMapping || nodes[i].parent == -2) continue;
    for (const OutlineEntry& e : nodes[i].entries) {
      if (e.key_begin <= offset && offset <= e.key_end && e.key_end > e.key_begin) {
        at.key = &e;
        at.key_mapping = static_cast<int>(i);
        break;
      }
    }
  }
  if (at.key) return at;
  const int node = o.node_at(offset);
  const OutlineNode& n = o.node(node);
  if ((n.kind == OutlineNode::kScalar || n.kind == OutlineNode::kAlias) && n.begin <= offset && offset <= n.end) {
    at.value = node;
    at.holder = holder_of(o, node, at.holder_mapping);
  }
  return at;
}

}  // namespace bodyfmt::lsp
