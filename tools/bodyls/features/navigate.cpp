// definition, references, prepare_rename and rename_link (language_features.h): a link's name
// (in this text, or where the model read it: a SubBody file) and every place that names it
// (parent, root_link, an extra joint's link1_name/link2_name), anchors and aliases, and the
// files a uri names.
#include "cursor.h"
#include "language_features.h"
#include "link_items.h"
#include "outline.h"
#include "schema.h"

#include <bodyfmt/body_writer.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

namespace bodyfmt::lsp {
namespace {

struct Context {
  explicit Context(const Document& d) : document(d), outline(d.text), index(d.text) {}
  const Document& document;
  Outline outline;
  TextIndex index;
  FileRange here(int node) const {
    const OutlineNode& n = outline.node(node);
    return {document.path, index.range(n.begin, n.end)};
  }
};

/// The name of the link the cursor is on (its `name` or a value naming it), with the node.
std::string link_name_at(const Context& c, std::size_t offset, int& node) {
  const AtCursor at = locate(c.outline, offset);
  node = -1;
  if (at.value < 0 || !at.holder || c.outline.node(at.value).kind != OutlineNode::kScalar) return {};
  const std::string kind = node_kind(c.outline, at.holder_mapping);
  const bool is_name = at.holder->key == "name" && is_link_kind(kind) && at.holder->value == at.value;
  if (!is_name && !names_a_link(kind, at.holder->key)) return {};
  node = at.value;
  return c.outline.node(at.value).scalar;
}

/// The scalars that name link `name` (not its own name), in file order.
std::vector<int> naming_scalars(const Outline& o, const std::string& name) {
  std::vector<int> found;
  for (std::size_t m = 0; m < o.nodes().size(); ++m) {
    const OutlineNode& map = o.node(static_cast<int>(m));
    if (map.kind != OutlineNode::kMapping || map.parent == -2) continue;
    std::optional<std::string> kind;  // worked out once a mapping, and only when it is needed
    for (const OutlineEntry& e : map.entries) {
      if (e.value < 0 || o.node(e.value).kind != OutlineNode::kScalar || o.node(e.value).scalar != name) continue;
      if (!kind) kind = node_kind(o, static_cast<int>(m));
      if (names_a_link(*kind, e.key)) found.push_back(e.value);
    }
  }
  std::sort(found.begin(), found.end(), [&](int a, int b) { return o.node(a).begin < o.node(b).begin; });
  return found;
}

/// The `name` values of the links called `name` (one, unless the file defines it twice).
std::vector<int> declarations(const Outline& o, const std::string& name) {
  std::vector<int> found;
  for (const LinkItem& link : link_items(o))
    if (link.name >= 0 && link.name_text == name) found.push_back(link.name);
  return found;
}

bool same_file(const std::string& a, const std::string& b) {
  if (a == b) return true;
  std::error_code ec, ec2;
  const std::filesystem::path ca = std::filesystem::weakly_canonical(a, ec);
  const std::filesystem::path cb = std::filesystem::weakly_canonical(b, ec2);
  return !ec && !ec2 && ca == cb;
}

/// Where the model read the name of the links called `name` that the text does not declare:
/// a SubBody file's `name` (the model's link names carry the SubBody's prefix and suffix, its
/// locations the included file), or a name this text writes in another form (a ContinuousTrack's
/// template, an alias), which only a model of the text as it is now can place.
std::vector<FileRange> model_declarations(const Document& d, const std::string& name, bool declared_here) {
  std::vector<FileRange> found;
  if (!d.model) return found;
  for (const Link& link : d.model->links) {
    if (link.name != name) continue;
    const SourceLocation at = link.sources.name();
    if (!at.known() || at.file.empty()) continue;
    const std::string& file = at.file.str();
    if (same_file(file, d.path) && (declared_here || !d.model_is_current)) continue;
    const TextPoint begin{at.line, at.column};
    FileRange range{file, {begin, begin}, true};
    found.push_back(std::move(range));
  }
  return found;
}

std::optional<std::string> resolve_file(const Document& d, const std::string& uri) {
  namespace fs = std::filesystem;
  std::string path = uri;
  if (path.rfind("file://", 0) == 0) path = path.substr(7);
  std::error_code ec;
  if (path.find("://") == std::string::npos && path.find('$') == std::string::npos && !path.empty()) {
    const fs::path candidate = fs::path(path).is_absolute() ? fs::path(path) : fs::path(d.path).parent_path() / path;
    if (fs::is_regular_file(candidate, ec)) return fs::weakly_canonical(candidate, ec).string();
  }
  // package:// and path variables: where the loader found the file, when it did.
  if (d.model)
    for (const Link& link : d.model->links)
      for (const Shape& shape : link.shapes)
        if (const MeshResource* mesh = geometry_if<MeshResource>(shape.geometry))
          if (mesh->uri == uri && !mesh->resolved_path.empty()) return mesh->resolved_path;
  return std::nullopt;
}

/// A name the loader reads back as `name` from one scalar, and can tell from the others.
bool acceptable_name(const std::string& name, std::string& why) {
  if (name.empty()) {
    why = "a link name cannot be empty";
    return false;
  }
  for (char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      why = "a link name cannot hold a line break or a control character";
      return false;
    }
  if (name.front() == ' ' || name.back() == ' ') {
    why = "a link name cannot begin or end with a space";
    return false;
  }
  return true;
}

}  // namespace

std::vector<FileRange> definition(const Document& document, TextPoint point) {
  const Context c(document);
  const std::size_t offset = c.index.offset(point);
  const AtCursor at = locate(c.outline, offset);
  if (at.value < 0) return {};
  const OutlineNode& value = c.outline.node(at.value);
  if (value.kind == OutlineNode::kAlias) {
    // The anchor defined last before the alias (a later one cannot be what it means).
    int best = -1;
    for (std::size_t i = 0; i < c.outline.nodes().size(); ++i) {
      const OutlineNode& n = c.outline.node(static_cast<int>(i));
      if (n.anchor == value.scalar && n.anchor_begin < value.begin &&
          (best < 0 || n.anchor_begin > c.outline.node(best).anchor_begin))
        best = static_cast<int>(i);
    }
    if (best < 0) return {};
    const OutlineNode& n = c.outline.node(best);
    return {{document.path, c.index.range(n.anchor_begin, n.anchor_end)}};
  }
  if (!at.holder) return {};
  int node = -1;
  const std::string name = link_name_at(c, offset, node);
  if (!name.empty()) {
    std::vector<FileRange> out;
    for (int d : declarations(c.outline, name)) out.push_back(c.here(d));
    for (FileRange& r : model_declarations(document, name, !out.empty())) out.push_back(std::move(r));
    return out;
  }
  const std::string& key = at.holder->key;
  if (key == "uri" || key == "url" || key == "model_file" || key == "modelFile") {
    if (auto file = resolve_file(document, value.scalar)) return {{*file, {{1, 1}, {1, 1}}}};
  }
  return {};
}

std::vector<FileRange> references(const Document& document, TextPoint point, bool include_declaration) {
  const Context c(document);
  int node = -1;
  const std::string name = link_name_at(c, c.index.offset(point), node);
  if (name.empty()) return {};
  std::vector<FileRange> out;
  if (include_declaration)
    for (int d : declarations(c.outline, name)) out.push_back(c.here(d));
  for (int n : naming_scalars(c.outline, name)) out.push_back(c.here(n));
  return out;
}

namespace {

/// The name node at `point` a rename would change, or -1 with `why`.
int rename_target(const Context& c, TextPoint point, std::string& name, std::string& why) {
  int node = -1;
  name = link_name_at(c, c.index.offset(point), node);
  if (name.empty()) {
    why = "the cursor is not on a link name (a link's name, or a parent, root_link or link1_name naming one)";
    return -1;
  }
  if (declarations(c.outline, name).empty()) {
    why = "no link is named \"" + name + "\"";
    return -1;
  }
  return node;
}

}  // namespace

std::optional<TextRange> prepare_rename(const Document& document, TextPoint point, std::string& why) {
  const Context c(document);
  std::string name;
  const int node = rename_target(c, point, name, why);
  if (node < 0) return std::nullopt;
  return c.here(node).range;
}

std::optional<std::vector<TextEdit>> rename_link(const Document& document, TextPoint point, const std::string& new_name,
                                                 std::string& why) {
  const Context c(document);
  std::string name;
  if (rename_target(c, point, name, why) < 0) return std::nullopt;
  if (!acceptable_name(new_name, why)) return std::nullopt;
  if (new_name == name) return std::vector<TextEdit>{};
  if (!declarations(c.outline, new_name).empty()) {
    why = "a link is already named \"" + new_name + "\"";
    return std::nullopt;
  }
  // A SubBody's links are named by the included file and its prefix: the model knows them.
  if (document.model && document.model->find_link(new_name) >= 0) {
    why = "the model already has a link named \"" + new_name + "\"";
    return std::nullopt;
  }
  std::vector<TextEdit> edits;
  // The .body writer's scalar: plain only where no YAML reader takes it for anything else,
  // else double-quoted with the escapes that keep every character (NEL, U+2028, U+2029 and
  // U+FFFE too) what it was.
  const std::string text = body_string(new_name);
  for (int d : declarations(c.outline, name)) edits.push_back({c.here(d), text});
  for (int n : naming_scalars(c.outline, name)) edits.push_back({c.here(n), text});
  return edits;
}

}  // namespace bodyfmt::lsp
