#include "yaml/yaml_node.h"

#include <type_traits>

namespace bodyfmt::yaml {

// The arena never runs destructors: everything it holds must be plain data.
static_assert(std::is_trivially_destructible_v<Node>);
static_assert(std::is_trivially_destructible_v<MapEntry>);
static_assert(std::is_trivially_destructible_v<NodeRef>);
static_assert(sizeof(Node) <= 56, "a node's size is multiplied by millions");

const SourceLocation& NodeRef::use_site() const { return alias_site != nullptr ? *alias_site : node->location; }

bool Node::is_null() const {
  // The YAML core-schema null spellings; only plain scalars, so `""` and `'null'` stay strings.
  if (kind != NodeKind::kScalar || !plain) return false;
  const std::string_view value = scalar();
  return value.empty() || value == "~" || value == "null" || value == "Null" || value == "NULL";
}

const MapEntry* Node::find(std::string_view key) const {
  // Mappings in body files hold a handful of keys, so a linear scan beats building an index.
  // The first byte settles almost every mismatch without a call to memcmp.
  if (key.empty()) return nullptr;
  for (const MapEntry& entry : entries()) {
    if (entry.key.size() == key.size() && entry.key[0] == key[0] && entry.key == key) return &entry;
  }
  return nullptr;
}

Node* Document::make_node() { return new (arena_.allocate(sizeof(Node), alignof(Node))) Node(); }

std::string_view Document::store(std::string_view text) {
  if (text.empty()) return std::string_view("", 0);
  char* copy = static_cast<char*>(arena_.allocate(text.size() + 1, 1));
  std::copy(text.begin(), text.end(), copy);
  copy[text.size()] = '\0';
  return std::string_view(copy, text.size());
}

const SourceLocation* Document::store(const SourceLocation& location) {
  return new (arena_.allocate(sizeof(SourceLocation), alignof(SourceLocation))) SourceLocation(location);
}

std::string_view Document::anchor_of(const Node* node) const {
  for (const auto& [name, anchored] : anchors) {
    if (anchored == node) return name;
  }
  return {};
}

std::string_view Document::tag_of(const Node* node) const {
  auto it = tags_.find(node);
  return it == tags_.end() ? std::string_view() : it->second;
}

}  // namespace bodyfmt::yaml
