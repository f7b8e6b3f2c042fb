#include "yaml/yaml_node.h"

namespace bodyfmt::yaml {

const SourceLocation& NodeRef::use_site() const { return alias_site ? *alias_site : node->location; }

bool Node::is_null() const {
  // The YAML core-schema null spellings; only plain scalars, so `""` and `'null'` stay strings.
  if (kind != NodeKind::kScalar || !plain) return false;
  return scalar.empty() || scalar == "~" || scalar == "null" || scalar == "Null" || scalar == "NULL";
}

const MapEntry* Node::find(std::string_view key) const {
  // Mappings in body files hold a handful of keys, so a linear scan beats building an index.
  for (const MapEntry& entry : entries) {
    if (entry.key == key) return &entry;
  }
  return nullptr;
}

Node* Document::make_node() { return &nodes_.emplace_back(); }

}  // namespace bodyfmt::yaml
