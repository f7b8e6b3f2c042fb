// document_symbols (language_features.h): the body, its link tree (a child link under its
// parent), and under each link its elements and devices as they nest.
#include "language_features.h"
#include "link_items.h"
#include "outline.h"
#include "schema.h"

#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>

namespace bodyfmt::lsp {
namespace {

constexpr int kMostElementDepth = 64;
constexpr int kMostLinkDepth = 256;

struct Builder {
  const Outline& o;
  const TextIndex& index;

  TextRange range_of(int node) const { return index.range(o.node(node).begin, o.node(node).end); }

  /// The element nodes of an `elements` value in its three forms (body-format-spec §7.1).
  void elements(int value, std::vector<Symbol>& out, int depth) const {
    if (value < 0 || depth > kMostElementDepth) return;
    const OutlineNode& v = o.node(value);
    if (v.kind == OutlineNode::kSequence) {
      for (int item : v.items) element(item, o.scalar_of(item, "type"), out, depth);
    } else if (v.kind == OutlineNode::kMapping) {
      if (o.find(value, "type")) {
        element(value, o.scalar_of(value, "type"), out, depth);
      } else {
        for (const OutlineEntry& e : v.entries) element(e.value, e.key, out, depth);
      }
    }
  }

  void element(int node, const std::string& type, std::vector<Symbol>& out, int depth) const {
    if (node < 0 || o.node(node).kind != OutlineNode::kMapping) return;
    const std::string kind = element_kind(type);
    Symbol s;
    s.kind = is_device_kind(kind) ? SymbolKind::kDevice : SymbolKind::kElement;
    s.detail = type.empty() ? "element without a type" : type;
    const OutlineEntry* name = o.find(node, "name");
    s.name = o.scalar_of(node, "name");
    if (s.name.empty()) s.name = type.empty() ? "(element)" : type;
    s.range = range_of(node);
    s.selection =
        name && name->value >= 0 ? range_of(name->value) : index.range(o.node(node).begin, o.node(node).begin);
    if (const OutlineEntry* inner = o.find(node, "elements")) elements(inner->value, s.children, depth + 1);
    // Visual and Collision's inline shape and resource.
    for (const char* key : {"shape", "resource"})
      if (const OutlineEntry* inline_node = o.find(node, key))
        element(inline_node->value, key == std::string("shape") ? "Shape" : "Resource", s.children, depth + 1);
    out.push_back(std::move(s));
  }
};

}  // namespace

std::vector<Symbol> document_symbols(const Document& document) {
  const Outline o(document.text);
  const TextIndex index(document.text);
  const Builder b{o, index};
  const std::vector<LinkItem> links = link_items(o);
  std::map<std::string, std::vector<std::size_t>> children;  // parent name -> link items
  std::set<std::string> names;
  for (const LinkItem& link : links)
    if (!link.name_text.empty()) names.insert(link.name_text);
  std::vector<std::size_t> roots;
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (!links[i].parent_text.empty() && names.count(links[i].parent_text) &&
        links[i].parent_text != links[i].name_text)
      children[links[i].parent_text].push_back(i);
    else
      roots.push_back(i);
  }
  std::vector<bool> placed(links.size(), false);
  // A link under its parent; each link once, so a cycle of parents cannot recurse forever.
  std::function<Symbol(std::size_t, int)> make = [&](std::size_t i, int depth) {
    placed[i] = true;
    const LinkItem& link = links[i];
    Symbol s;
    s.kind = SymbolKind::kLink;
    s.name = link.name_text.empty() ? "(link without a name)" : link.name_text;
    const std::string type = o.scalar_of(link.mapping, "type");
    std::string joint = o.scalar_of(link.mapping, "joint_type");
    if (joint.empty()) joint = o.scalar_of(link.mapping, "jointType");
    s.detail = type == "SubBody" ? "SubBody" : (joint.empty() ? "fixed" : joint);
    s.range = b.range_of(link.mapping);
    s.selection =
        link.name >= 0 ? b.range_of(link.name) : index.range(o.node(link.mapping).begin, o.node(link.mapping).begin);
    if (const OutlineEntry* e = o.find(link.mapping, "elements")) b.elements(e->value, s.children, 0);
    // Deeper than kMostLinkDepth, a chain goes on at the top level (below): the stack stays small.
    if (!link.name_text.empty() && depth < kMostLinkDepth)
      for (std::size_t child : children[link.name_text])
        if (!placed[child]) s.children.push_back(make(child, depth + 1));
    return s;
  };
  Symbol body;
  body.kind = SymbolKind::kBody;
  body.name = o.scalar_of(o.root(), "name");
  if (body.name.empty()) body.name = std::filesystem::path(document.path).stem().string();
  if (body.name.empty()) body.name = "(body)";
  body.detail = "body";
  body.range = index.range(0, document.text.size());
  body.selection = index.range(0, 0);
  if (const OutlineEntry* name = o.find(o.root(), "name"); name && name->value >= 0)
    body.selection = b.range_of(name->value);
  for (std::size_t r : roots)
    if (!placed[r]) body.children.push_back(make(r, 0));
  // Links on a cycle of parents, and the rest of very deep chains: at the top, once each.
  for (std::size_t i = 0; i < links.size(); ++i)
    if (!placed[i]) body.children.push_back(make(i, 0));
  return {body};
}

}  // namespace bodyfmt::lsp
