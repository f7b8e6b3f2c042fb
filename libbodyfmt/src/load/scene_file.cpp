#include "load/scene_file.h"

#include <bodyfmt/body_keys.h>

#include "load/mapping_reader.h"
#include "load/resource_reader.h"
#include "load/scalar.h"
#include "load/uri.h"
#include "mesh_import/scene_tree.h"

#include <algorithm>
#include <filesystem>

namespace bodyfmt::detail {

yaml::NodeRef SceneFiles::value_of(const yaml::NodeRef& node, std::string_view key) {
  const yaml::MapEntry* entry = node->find(key);
  return entry ? node.child(entry->value) : yaml::NodeRef{};
}

bool SceneFiles::find_named(const yaml::NodeRef& elements, std::string_view name, const Eigen::Matrix3d& above,
                            yaml::NodeRef& found, Eigen::Matrix3d& found_above) {
  if (!elements) return false;
  // The forms of `scene` and `elements`: a list of nodes, one node with a type, or a mapping
  // keyed by type (visited in key order, as the element reader visits it).
  std::vector<std::pair<yaml::NodeRef, std::string>> nodes;
  if (elements->is_sequence()) {
    for (const yaml::NodeRef& item : elements->items()) {
      const yaml::MapEntry* type = item->is_mapping() ? item->find("type") : nullptr;
      if (type && type->value->is_scalar())
        nodes.emplace_back(elements.child(item), std::string(type->value->scalar()));
    }
  } else if (elements->is_mapping()) {
    if (const yaml::MapEntry* type = elements->find("type"); type && type->value->is_scalar()) {
      nodes.emplace_back(elements, std::string(type->value->scalar()));
    } else {
      std::vector<const yaml::MapEntry*> keyed;
      for (const yaml::MapEntry& e : elements->entries()) keyed.push_back(&e);
      std::sort(keyed.begin(), keyed.end(), [](auto* a, auto* b) { return a->key < b->key; });
      for (const yaml::MapEntry* e : keyed)
        if (e->value->is_mapping()) nodes.emplace_back(elements.child(e->value), std::string(e->key));
    }
  }
  for (const auto& [node, type] : nodes) {
    const yaml::MapEntry* node_name = node->find("name");
    if (node_name && node_name->value->is_scalar() && node_name->value->scalar() == name) {
      found = node;
      found_above = above;
      return true;
    }
    if (const yaml::MapEntry* children = node->find("elements")) {
      // Only a Transform turns or scales what is under it (its translation is dropped here).
      Eigen::Matrix3d inner = above;
      if (type == "Transform")
        inner = above * read_node_transform(ctx_, {}, value_of(node, "rotation"), value_of(node, "scale"),
                                            value_of(node, "scale_orientation"))
                            .linear();
      if (find_named(node.child(children->value), name, inner, found, found_above)) return true;
    }
  }
  return false;
}

void SceneFiles::read(ElementReader& reader, const SourceLocation& uri, const std::string& path,
                      const MeshResource& resource, const ElementFrame& frame, const yaml::NodeRef& node) {
  const std::string identity = file_identity(path);
  if (std::find(chain_.begin(), chain_.end(), identity) != chain_.end()) {
    ctx_.report("scene-recursion", uri, "scene files include each other: " + include_chain_text(chain_, identity));
    return;
  }
  if (chain_.size() >= kMaxNesting) {
    ctx_.report("scene-recursion", uri,
                "scene files nest deeper than " + std::to_string(kMaxNesting) + "; this one is not read");
    return;
  }
  if (expanded_nodes_ > options_.max_expanded_yaml_nodes) return;  // reported where the budget ran out
  const File& file = load(uri, path, identity);
  if (!file.scene) return;
  // Each file nested in the next adds its depth to the readers' recursion: together they are
  // bounded as one document is (--max-yaml-depth), so that no stack runs out.
  if (chain_depth_ + file.depth > options_.max_yaml_depth) {
    ctx_.report("scene-recursion", uri,
                "resources nested in one another are deeper than " + std::to_string(options_.max_yaml_depth) +
                    " YAML levels together; this one is not read");
    return;
  }
  // A scene file named many times by scene files named many times multiplies: the shapes
  // of every use are the model's, so the uses together are bounded as one document is.
  expanded_nodes_ += file.document->expanded_node_count;
  if (expanded_nodes_ > options_.max_expanded_yaml_nodes) {
    ctx_.report("scene-expansion", uri,
                "the scene files this body includes expand to more than " +
                    std::to_string(options_.max_expanded_yaml_nodes) +
                    " YAML nodes; this and every later scene file use are not read");
    return;
  }

  ElementFrame inner = frame;
  // StdSceneLoader: the length unit scales every length of the scene, the upper axis turns
  // it on top of that (AbstractSceneLoader::insertTransformNodeToAdjustUpperAxis).
  if (resource.length_scale != 1.0 || resource.y_up) {
    Eigen::Affine3d X = Eigen::Affine3d::Identity();
    X.linear() = (resource.y_up ? mesh::y_up_rotation() : Eigen::Matrix3d::Identity()) * resource.length_scale;
    inner = reader.push_frame(frame, X);
  }
  inner.scene_file = true;
  inner.scene_top = true;
  inner.scene_length_scale = resource.length_scale;

  const bool degrees = ctx_.degrees;
  const bool own_angle_unit = ctx_.own_angle_unit;
  ctx_.degrees = file.degrees;
  ctx_.own_angle_unit = true;
  chain_.push_back(identity);
  chain_depth_ += file.depth;
  yaml::NodeRef scene = file.scene;
  if (node) {
    // Re-centred as adjustNodeCoordinate does: the node keeps the linear part above it and its
    // own; its own translation is cancelled by the frame it is read under.
    yaml::NodeRef named;
    Eigen::Matrix3d above = Eigen::Matrix3d::Identity();
    const std::string name = node->is_scalar() ? std::string(node->scalar()) : std::string();
    if (!find_named(file.scene, name, Eigen::Matrix3d::Identity(), named, above)) {
      ctx_.report("mesh-node-not-found", node,
                  "node \"" + name + "\" is not found in \"" + std::filesystem::path(path).filename().string() + "\"",
                  "name a node of the scene file, or remove node:");
      scene = {};
    } else {
      Eigen::Affine3d X = Eigen::Affine3d::Identity();
      X.linear() = above;
      const yaml::MapEntry* type = named->find("type");
      if (type && type->value->is_scalar() && type->value->scalar() == "Transform")
        X.translate(-read_node_transform(ctx_, value_of(named, "translation"), {}, {}, {}).translation());
      inner = reader.push_frame(inner, X);
      inner.scene_top = true;
      scene = named;
    }
  }
  if (scene) reader.read_elements(scene, inner);
  chain_depth_ -= file.depth;
  chain_.pop_back();
  ctx_.degrees = degrees;
  ctx_.own_angle_unit = own_angle_unit;
}

void SceneFiles::read_as_geometry(ElementReader& reader, Shape shape, const ElementFrame& frame) {
  const MeshResource& resource = geometry_get<MeshResource>(shape.geometry);
  std::vector<Shape>& shapes = reader.model().links[static_cast<std::size_t>(reader.link_index())].shapes;
  const std::size_t first = shapes.size();
  const int errors = ctx_.errors;
  read(reader, resource.uri_source, resource.resolved_path, resource, frame);
  if (shapes.size() == first && ctx_.errors != errors) return;  // the file could not be read: reported
  // The shape must sit where the geometry's Shape node puts it: the length unit may scale it,
  // nothing may move or turn it (an upper axis is a transform above it too).
  Eigen::Affine3d expected = Eigen::Affine3d::Identity();
  expected.linear() *= resource.length_scale;
  expected = frame.X_LF * expected;
  const bool single = shapes.size() == first + 1 && !resource.y_up &&
                      shapes.back().X_LS.matrix().isApprox(expected.matrix().topRows<3>(), 1e-12);
  if (!single) {
    const std::size_t added = shapes.size() - first;
    const std::string what = added == 0   ? "has no shape"
                             : added == 1 ? "moves or turns its shape"
                                          : "has " + std::to_string(added) + " shapes";
    ctx_.report("scene-unsupported", resource.uri_source,
                "a scene file given as a geometry must be a single shape with no transform of its own; this one " +
                    what + ", so Choreonoid refuses it",
                "name it by a Resource node instead of a geometry");
    shapes.resize(first);
    return;
  }
  Shape& added = shapes.back();
  // readResourceAsGeometry keeps only the mesh: name and appearance are the Shape node's.
  added.name = shape.name;
  added.appearance = shape.appearance;
}

const SceneFiles::File& SceneFiles::load(const SourceLocation& uri, const std::string& path,
                                         const std::string& identity) {
  auto [it, inserted] = files_.try_emplace(identity);
  File& file = it->second;
  if (!inserted) return file;
  std::string why;
  const std::optional<std::string> text = read_included_file(path, options_, why);
  if (!text) {
    ctx_.report("resource-missing", uri, "scene file \"" + path + "\" cannot be read: " + why);
    return file;
  }
  yaml::ParseOptions po;
  po.max_expanded_nodes = options_.max_expanded_yaml_nodes;
  po.max_depth = options_.max_yaml_depth;
  // A scene file is a document of its own: StdSceneLoader reads it with a new YAML reader,
  // which sees no anchor of the body file.
  file.document = yaml::parse_yaml(*text, path, po, ctx_.sink);
  if (file.document && file.document->root) {
    if (file.document->root->is_mapping()) note_model_text(options_, path);
    file.depth = file.document->root->expanded_depth;
    read_header(file);
  }
  return file;
}

void SceneFiles::read_header(File& file) {
  const yaml::NodeRef root = file.document->root;
  if (!root->is_mapping()) {
    ctx_.report("scene-header", root, "a scene file must be a mapping of header keys and a scene");
    return;
  }
  MappingReader r(ctx_, root, "scene file");
  // StdSceneLoader never reads `format`; its writer writes choreonoid_scene, the files
  // of Choreonoid's share folder ChoreonoidScene.
  if (yaml::NodeRef format = r.take({"format"});
      format && format->scalar() != "choreonoid_scene" && format->scalar() != "ChoreonoidScene") {
    ctx_.report("scene-format-name", format,
                "the format \"" + std::string(format->scalar()) +
                    "\" is not a Choreonoid scene; Choreonoid does not check it and reads the file as one",
                "write format: choreonoid_scene");
  }
  yaml::NodeRef version = r.take({"format_version", "formatVersion"});
  yaml::NodeRef unit = r.take({"angle_unit", "angleUnit"});
  yaml::NodeRef scene = r.take({"scene"});
  r.report_unknown(body_key_names("scene"));
  if (!version) {
    ctx_.report("scene-header", root, "the version of the Choreonoid scene file format is not specified",
                "add format_version: 2.0");
    return;
  }
  const std::optional<double> v = required_double(ctx_, version);
  if (!v) return;
  if (*v >= 2.1) {
    ctx_.report("scene-header", version,
                "version " + std::string(version->scalar()) + " of the Choreonoid scene file format is not supported");
    return;
  }
  if (unit) {
    if (unit->scalar() == "radian") {
      if (*v >= 2.0) {
        ctx_.report("scene-header", unit, "radian mode is not supported in scene file format version 2.0",
                    "write angles in degrees, or use format_version: 1.0");
        return;
      }
      file.degrees = false;
    } else if (unit->scalar() != "degree") {
      ctx_.report("scene-header", unit, "the angle_unit value must be either \"radian\" or \"degree\"");
      return;
    }
  }
  if (!scene) {
    ctx_.report("scene-header", root, "the scene file has no \"scene\" key; Choreonoid loads nothing from it");
    return;
  }
  if ((scene->is_sequence() && scene->items().empty()) || (scene->is_mapping() && scene->entries().empty()))
    ctx_.report("scene-empty", scene, "the scene of this scene file is empty; it adds no shape");
  file.scene = scene;
}

}  // namespace bodyfmt::detail
