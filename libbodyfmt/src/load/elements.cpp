#include "load/elements.h"

#include <bodyfmt/body_keys.h>

#include "load/appearance.h"
#include "load/devices.h"
#include "load/geometry.h"
#include "load/mapping_reader.h"
#include "load/scalar.h"
#include "load/values.h"
#include "text/text_util.h"

#include <algorithm>

namespace bodyfmt::detail {
namespace {

bool is_scene_only_type(std::string_view t) {
  return t == "LineSet" || t == "DirectionalLight" || t == "PerspectiveCamera" || t == "OrthographicCamera" ||
         t == "Fog" || t == "Text";
}

/// The node types Choreonoid's scene reader defines, the only ones a .scen file may use.
const std::vector<std::string_view>& scene_file_types() {
  static const std::vector<std::string_view> types = {
      "DirectionalLight", "Fog",      "Group", "LineSet",   "Node", "OrthographicCamera", "PerspectiveCamera",
      "PointLight",       "Resource", "Shape", "SpotLight", "Text", "Transform"};
  return types;
}

bool is_scene_file_type(std::string_view t) {
  const auto& types = scene_file_types();
  return std::find(types.begin(), types.end(), t) != types.end();
}

/// `appearance` written under a Shape's `geometry` (one level too deep, where Choreonoid
/// ignores it): a warning that says where it belongs and, when it is the last key of the
/// geometry written in block style and the Shape has no appearance of its own, the fix-it
/// that moves its lines up to the Shape's indentation (unsafe: the material is then read).
void report_misplaced_appearance(LoadContext& ctx, const yaml::NodeRef& shape, const yaml::NodeRef& geometry) {
  if (!geometry->is_mapping()) return;
  const yaml::MapEntry* appearance = geometry->find("appearance");
  const yaml::MapEntry* geometry_key = shape->find("geometry");
  if (!appearance || !geometry_key) return;
  const yaml::MapEntry* own = shape->find("appearance");
  std::vector<FixIt> fixes;
  const std::optional<EntryLines> lines =
      own || &geometry->entries().back() != appearance ? std::nullopt : entry_lines(ctx, geometry, *appearance);
  const std::size_t shape_indent = static_cast<std::size_t>(std::max(geometry_key->key_location.column - 1, 0));
  if (lines && lines->indent > shape_indent) {
    const std::string_view text = ctx.text.substr(lines->begin, lines->end - lines->begin);
    const std::size_t up = lines->indent - shape_indent;
    std::string moved;
    for (std::size_t at = 0; at < text.size();) {
      std::size_t next = text.find('\n', at);
      next = next == std::string_view::npos ? text.size() : next + 1;
      std::size_t spaces = 0;
      while (spaces < up && at + spaces < next && text[at + spaces] == ' ') ++spaces;
      moved.append(text.substr(at + spaces, next - at - spaces));
      at = next;
    }
    FixIt fix;
    fix.file = appearance->key_location.file;
    fix.begin = lines->begin;
    fix.end = lines->end;
    fix.line = appearance->key_location.line;
    fix.column = 1;
    fix.original = std::string(text);
    fix.replacement = std::move(moved);
    fix.safety = FixSafety::kUnsafe;
    fixes.push_back(std::move(fix));
  }
  ctx.report("load-misplaced-key", appearance->key_location,
             "\"appearance\" is written inside geometry, where Choreonoid ignores it (the shape gets the default "
             "material); it belongs to the Shape node, one level up, beside \"geometry\"",
             own ? "the Shape has an appearance already (line " + std::to_string(own->key_location.line) +
                       "): keep the one you mean there and remove this one"
                 : "move it one level up: indent it as geometry is indented",
             std::move(fixes));
}

}  // namespace

ElementReader::ElementReader(LoadContext& ctx, Model& model, LinkIndex link, ResourceHandler* resources)
    : ctx_(ctx), model_(model), link_(link), resources_(resources) {}

void ElementReader::read_elements(const yaml::NodeRef& elements, const ElementFrame& outer) {
  if (!elements) return;
  ElementFrame frame = outer;
  frame.scene_top = false;
  if (elements->is_sequence()) {
    for (const yaml::NodeRef& raw_item : elements->items()) {
      const yaml::NodeRef item = elements.child(raw_item);
      if (!item->is_mapping()) {
        ctx_.report("load-type", item, "an element must be a mapping");
        continue;
      }
      const yaml::MapEntry* type = item->find("type");
      if (!type) {
        ctx_.report("load-missing-key", item, "key \"type\" is not found in this element");
        continue;
      }
      read_node(item, std::string(type->value->scalar()), frame);
    }
    return;
  }
  if (elements->is_mapping()) {
    if (const yaml::MapEntry* type = elements->find("type")) {
      if (outer.scene_file && !outer.scene_top) {
        // Choreonoid's scene reader reads every key of an `elements` mapping as a node type
        // and refuses `type: X`, whose value is not a mapping.
        ctx_.report("load-type", elements.child(type->value),
                    "in a scene file, an elements mapping is keyed by node type; this node cannot be read",
                    "write elements as a list: - type: " + std::string(type->value->scalar()));
        return;
      }
      read_node(elements, std::string(type->value->scalar()), frame);
      return;
    }
    // body-format-spec §7.1 form 3: keys are node types, visited in byte-wise order.
    std::vector<const yaml::MapEntry*> entries;
    for (const yaml::MapEntry& e : elements->entries()) entries.push_back(&e);
    std::sort(entries.begin(), entries.end(),
              [](const yaml::MapEntry* a, const yaml::MapEntry* b) { return a->key < b->key; });
    for (const yaml::MapEntry* e : entries) {
      if (!e->value->is_mapping()) {
        ctx_.report("load-type", e->value, "the \"" + std::string(e->key) + "\" element must be a mapping");
        continue;
      }
      if (const yaml::MapEntry* inner = e->value->find("type"); inner && inner->value->scalar() != e->key) {
        ctx_.report("load-type-mismatch", inner->value,
                    "the node type \"" + std::string(inner->value->scalar()) + "\" is different from the type \"" +
                        std::string(e->key) + "\" specified in the parent node");
        continue;
      }
      read_node(elements.child(e->value), std::string(e->key), frame);
    }
    return;
  }
  ctx_.report("load-type", elements, "a value of the \"elements\" key must be a sequence or a mapping");
}

Eigen::Affine3d read_node_transform(LoadContext& ctx, const yaml::NodeRef& translation, const yaml::NodeRef& rotation,
                                    const yaml::NodeRef& scale, const yaml::NodeRef& scale_orientation) {
  Eigen::Affine3d X = Eigen::Affine3d::Identity();
  if (translation)
    if (auto v = read_translation(ctx, translation)) X.translation() = *v;
  if (rotation)
    if (auto R = read_rotation(ctx, rotation)) X.linear() = *R;
  if (scale) {
    if (!scale->is_sequence()) {
      // body-format-spec §4.4: a scalar scale is silently ignored by Choreonoid.
      ctx.report("load-ignored-value", scale, "scale must be a 3-element sequence; Choreonoid ignores a scalar",
                 "write [sx, sy, sz]");
    } else if (auto v = read_vec3(ctx, scale)) {
      Eigen::Matrix3d S = v->asDiagonal();
      // A scene file's Transform scales along the axes of its scale_orientation (SgScaleTransform).
      if (scale_orientation)
        if (auto R = read_rotation(ctx, scale_orientation)) S = *R * S * R->transpose();
      X.linear() = X.linear() * S;
    }
  } else if (scale_orientation) {
    ctx.report("load-ignored-key", scale_orientation.use_site(),
               "scale_orientation without scale has no effect; Choreonoid does not read it");
  }
  return X;
}

std::optional<ElementFrame> ElementReader::enter(MappingReader& r, const ElementFrame& frame, bool allow_scale,
                                                 const yaml::NodeRef& scale_orientation) {
  const yaml::NodeRef translation = r.take({"translation"});
  const yaml::NodeRef rotation = r.take({"rotation"});
  const yaml::NodeRef scale = allow_scale ? r.take({"scale"}) : yaml::NodeRef{};
  return push_frame(frame, read_node_transform(ctx_, translation, rotation, scale,
                                               allow_scale ? scale_orientation : yaml::NodeRef{}));
}

ElementFrame ElementReader::push_frame(const ElementFrame& frame, const Eigen::Affine3d& X_PF) {
  ElementFrame inner = frame;
  inner.X_LF = frame.X_LF * X_PF;
  link().frames.push_back(SceneFrame{frame.frame, -1, X_PF});
  inner.frame = static_cast<int>(link().frames.size()) - 1;
  return inner;
}

void ElementReader::read_node(const yaml::NodeRef& node, const std::string& type, const ElementFrame& frame) {
  if (!node->is_mapping()) {
    ctx_.report("load-type", node, "a " + type + " node must be a mapping");
    return;
  }
  if (frame.scene_file) {
    if (!is_scene_file_type(type)) return report_undefined_type(node, type, frame);
    if (type == "PointLight" || type == "SpotLight") {  // scene lights in a scene file, not devices
      ctx_.report("load-scene-node", node, "a " + type + " node has no meaning in a body model; it is ignored");
      return;
    }
  }
  if (type == "Skip") return;
  if (type == "Group" || type == "Transform") {
    MappingReader r(ctx_, node, type + " node");
    r.take({"type"});
    r.take({"name"});
    ElementFrame inner = frame;
    if (type == "Transform") {
      const yaml::NodeRef scale_orientation = frame.scene_file ? r.take({"scale_orientation"}) : yaml::NodeRef{};
      inner = *enter(r, frame, true, scale_orientation);
      // body-format-spec §6.4 rule 5: mass keys on a Transform are ignored by Choreonoid.
      for (KeyNames names :
           {KeyNames{"mass"}, KeyNames{"center_of_mass", "centerOfMass", "centerofMass"}, KeyNames{"inertia"}}) {
        if (auto ignored = r.take(names)) {
          ctx_.report("load-mass-ignored", ignored, "mass properties on a Transform node are ignored by Choreonoid",
                      "move them into a RigidBody node");
        }
      }
    } else if (type == "Group" && r.has({"translation", "rotation", "scale"})) {
      for (const char* k : {"translation", "rotation", "scale"}) {
        if (auto ignored = r.take({k}))
          ctx_.report("load-ignored-key", ignored, std::string("a Group has no ") + k + "; it is ignored",
                      "use a Transform node");
      }
    }
    read_elements(r.take({"elements"}), inner);
    r.report_unknown(body_key_names(frame.scene_file ? "scene:Transform" : "element:Transform"));
    return;
  }
  if (type == "RigidBody") return read_rigid_body(node, frame);
  if (type == "Visual") return read_part(node, ModelPart::kVisual, frame);
  if (type == "Collision") return read_part(node, ModelPart::kCollision, frame);
  if (type == "Shape") return read_shape(node, frame);
  if (type == "Resource") {
    if (resources_) {
      resources_->read_resource(*this, node, frame);
    } else {
      ctx_.report("resource-unsupported", node, "Resource nodes are not supported by this loader");
    }
    return;
  }
  if (is_core_device_type(type) || is_plugin_node_type(type)) return read_device(node, type, frame);
  if (type == "Node") {
    // Choreonoid's scene reader makes an empty node of it (StdSceneReader's readNodeNode):
    // nothing under it is read, mass and devices included, and it says nothing. A Node without
    // elements is a named marker (Choreonoid's WRS2018 HoseConnector has one): nothing is lost.
    if (const yaml::MapEntry* elements = node->find("elements"); elements && !elements->value->is_null())
      ctx_.report("load-ignored-key", elements->key_location,
                  "a Node is an empty scene node to Choreonoid: its elements (shapes, mass, devices) are ignored",
                  "use a Group, or a Transform to place them");
    return;
  }
  if (is_scene_only_type(type)) {
    ctx_.report("load-scene-node", node, "a " + type + " node has no meaning in a body model; it is ignored");
    if (type == "PerspectiveCamera" && node->is_mapping())  // its field_of_view is an angle (§8.8)
      if (const yaml::MapEntry* fov = node->find("field_of_view")) ctx_.note_angle(node.child(fov->value));
    return;
  }
  report_undefined_type(node, type, frame);
}

void ElementReader::report_undefined_type(const yaml::NodeRef& node, const std::string& type,
                                          const ElementFrame& frame) {
  // body-format-spec §7.2 rule 3; a scene file knows only the scene reader's types.
  MappingReader r(ctx_, node, type);
  yaml::NodeRef optional = r.take({"is_optional", "isOptional"});
  bool is_optional = optional && text::parse_bool_word(optional->scalar()).value_or(false);
  std::string_view guess = text::suggest(type, frame.scene_file ? scene_file_types() : element_type_names());
  const yaml::MapEntry* type_entry = node->find("type");
  yaml::NodeRef at = type_entry ? type_entry->value : node;
  ctx_.report(is_optional ? "load-optional-node-skipped" : "load-unknown-node-type", at,
              "the node type \"" + type + "\" is not defined" +
                  (frame.scene_file ? std::string(" in a Choreonoid scene file") : std::string()) +
                  (is_optional ? std::string("; this optional node is skipped") : std::string()),
              guess.empty() ? std::string() : "did you mean " + std::string(guess) + "?");
}

void ElementReader::read_part(const yaml::NodeRef& node, ModelPart part, const ElementFrame& frame) {
  const char* name = part == ModelPart::kVisual ? "Visual" : "Collision";
  MappingReader r(ctx_, node, std::string(name) + " node");
  r.take({"type"});
  r.take({"name"});
  if (frame.part != ModelPart::kBoth && frame.part != part) {
    ctx_.report("load-visual-collision-conflict", node,
                std::string("this ") + name + " node is inside a " +
                    (part == ModelPart::kVisual ? "Collision" : "Visual") + " node defined at a higher level");
    return;
  }
  ElementFrame inner = *enter(r, frame);
  inner.part = part;
  inner.part_source = node.use_site();
  // Inline shortcuts come before `elements` (body-format-spec §8.4).
  // Both are findMapping reads in Choreonoid: a value of another type is skipped.
  if (auto resource = r.take({"resource"})) {
    if (mapping_or_ignored(ctx_, resource, "resource") && resources_) resources_->read_resource(*this, resource, inner);
  }
  if (auto shape = r.take({"shape"})) {
    if (mapping_or_ignored(ctx_, shape, "shape")) read_shape(shape, inner);
  }
  read_elements(r.take({"elements"}), inner);
  r.report_unknown(body_key_names("element:Visual"));
}

void ElementReader::read_rigid_body(const yaml::NodeRef& node, const ElementFrame& frame) {
  MappingReader r(ctx_, node, "RigidBody node");
  r.take({"type"});
  r.take({"name"});
  ElementFrame inner = *enter(r, frame);
  MassContribution c;
  c.source = node.use_site();
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  if (auto v = r.take({"center_of_mass", "centerOfMass"})) {
    // A findListing read here (unlike the link's own key): another type leaves the origin.
    if (listing_or_ignored(ctx_, v, "center_of_mass"))
      if (auto x = read_vec3(ctx_, v)) com = *x;
  }
  if (auto v = r.take({"mass"})) {
    if (auto m = optional_double(ctx_, v)) c.mass = *m;
  }
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  if (auto v = r.take({"inertia"})) {
    if (v->is_sequence()) {
      if (auto x = read_inertia(ctx_, v))
        I = *x;
      else
        c.inertia_refused = true;
    } else {
      ctx_.report("load-ignored-value", v, "a RigidBody inertia that is not a sequence is read as zero");
    }
  }
  // body-format-spec §6.4 rule 1: the accumulated transform, scale included.
  const Eigen::Matrix3d L = inner.X_LF.linear();
  c.center_of_mass = inner.X_LF * com;
  c.inertia = L * I * L.transpose();
  link().frames[static_cast<std::size_t>(inner.frame)].rigid_body = static_cast<int>(link().mass_contributions.size());
  link().mass_contributions.push_back(c);
  ++rigid_bodies_;
  read_elements(r.take({"elements"}), inner);
  r.report_unknown(body_key_names("element:RigidBody"));
}

void ElementReader::read_shape(const yaml::NodeRef& node, const ElementFrame& frame) {
  if (!node->is_mapping()) {
    ctx_.report("load-type", node, "a Shape node must be a mapping");
    return;
  }
  MappingReader r(ctx_, node, "Shape node");
  r.take({"type"});
  Shape shape;
  shape.division_number = ctx_.default_division_number;
  if (auto name = r.take({"name"})) shape.name = name->scalar();
  ElementFrame inner = *enter(r, frame);
  shape.source = node.use_site();
  if (auto geometry = r.take({"geometry"})) {
    report_misplaced_appearance(ctx_, node, geometry);
    auto g = read_geometry(ctx_, geometry, shape.division_number);
    if (!g) return;
    shape.geometry = std::move(*g);
  } else {
    return;  // an empty Shape is legal and produces nothing
  }
  if (auto appearance = r.take({"appearance"})) shape.appearance = read_appearance(ctx_, appearance);
  if (auto material = r.take({"material"})) {
    ctx_.report("load-ignored-key", material, "\"material\" directly on a Shape is ignored by Choreonoid",
                "move it under appearance");
  }
  r.take({"is_meta_scene"});
  r.report_unknown(body_key_names("element:Shape"));
  if (resources_ && geometry_is<MeshResource>(shape.geometry) && resources_->read_scene_geometry(*this, shape, inner))
    return;
  add_shape(std::move(shape), inner);
}

void ElementReader::add_shape(Shape shape, const ElementFrame& frame) {
  shape.X_LS = frame.X_LF;
  shape.frame = frame.frame;
  shape.visual = frame.part != ModelPart::kCollision;
  shape.collision = frame.part != ModelPart::kVisual;
  link().shapes.push_back(std::move(shape));
}

void ElementReader::read_device(const yaml::NodeRef& node, const std::string& type, const ElementFrame& frame) {
  MappingReader r(ctx_, node, type + " device");
  r.take({"type"});
  Device d;
  d.node_type = type;
  d.link = link_;
  d.source = node.use_site();
  for (const yaml::MapEntry& e : node->entries()) {
    if (e.value->is_scalar()) d.keys[std::string(e.key)] = e.value->scalar();
    d.key_sources[std::string(e.key)] = node.child(e.value).use_site();
  }
  if (auto name = r.take({"name"})) d.name = name->scalar();
  if (auto id = r.take({"id"})) {
    if (auto v = optional_int(ctx_, id)) d.id = static_cast<int>(*v);
  }
  if (auto on = r.take({"on"})) {
    if (auto v = optional_bool(ctx_, on)) d.on = *v;
  }
  r.take({"is_optional", "isOptional"});
  ElementFrame inner = *enter(r, frame);
  // A device frame is rigid; scale on an enclosing node only affects its child shapes.
  // Choreonoid's readDevice takes the whole linear part of the transform stack, scale
  // included, as the device's "rotation": say where the two differ.
  const Eigen::Matrix3d L = inner.X_LF.linear();
  d.X_LD.linear() = inner.X_LF.rotation();
  d.X_LD.translation() = inner.X_LF.translation();
  if ((L.transpose() * L - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9)
    ctx_.report("device-scaled-frame", node,
                "this device is under a scaled node: Choreonoid's device rotation here is the scaled, "
                "non-orthonormal matrix; bodyfmt keeps its pure rotation",
                "move the device out of the scaled Transform, or scale the shapes only");
  yaml::NodeRef elements = r.take({"elements"});
  if (is_plugin_node_type(type)) {
    d.plugin = true;
    d.type = type;
    // Particle devices (SceneEffects plugin): emission_range is an angle (§3).
    note_first_angle(r, {"emission_range", "emissionRange"}, false);
    for (const yaml::MapEntry& e : node->entries()) r.ignore(e.key);
    if (ctx_.reported_once.insert("plugin:" + type).second) {
      ctx_.report("load-plugin-node", node,
                  "\"" + type +
                      "\" is a plugin node type: Choreonoid loads it only with its plugin; "
                      "it is kept as an opaque device");
    }
    model_.devices.push_back(std::move(d));
    read_elements(elements, inner);
    return;
  }
  bool keep = read_device_params(r, type, d);
  r.report_unknown(body_key_names("device"));
  if (keep) model_.devices.push_back(std::move(d));
  read_elements(elements, inner);
}

}  // namespace bodyfmt::detail
