#include "link_items.h"

namespace bodyfmt::lsp {
namespace {

int scalar_value(const Outline& o, int mapping, std::string_view key) {
  const OutlineEntry* e = o.find(mapping, key);
  if (!e || e->value < 0 || o.node(e->value).kind != OutlineNode::kScalar) return -1;
  return e->value;
}

}  // namespace

std::vector<LinkItem> link_items(const Outline& o) {
  std::vector<LinkItem> links;
  if (o.node(o.root()).kind != OutlineNode::kMapping) return links;
  const OutlineEntry* entry = o.find(o.root(), "links");
  if (!entry || entry->value < 0) return links;
  const OutlineNode& holder = o.node(entry->value);
  std::vector<int> mappings;
  if (holder.kind == OutlineNode::kSequence) mappings = holder.items;
  for (const OutlineEntry& e : holder.entries) mappings.push_back(e.value);
  for (int m : mappings) {
    if (m < 0 || o.node(m).kind != OutlineNode::kMapping) continue;
    LinkItem item;
    item.mapping = m;
    item.name = scalar_value(o, m, "name");
    item.parent = scalar_value(o, m, "parent");
    if (item.name >= 0) item.name_text = o.node(item.name).scalar;
    if (item.parent >= 0) item.parent_text = o.node(item.parent).scalar;
    links.push_back(std::move(item));
  }
  return links;
}

}  // namespace bodyfmt::lsp
