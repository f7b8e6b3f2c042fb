#include "schema.h"

#include <algorithm>
#include <cstdlib>

namespace bodyfmt::lsp {
namespace {

std::string link_kind(const Outline& o, int node) {
  const std::string type = o.scalar_of(node, "type");
  if (type == "SubBody" || type == "ContinuousTrack") return "link:" + type;
  return "link";
}

/// The kind of a node reached from its parent mapping's entry `key`, the parent being `parent_kind`.
std::string kind_under_key(const Outline& o, int node, std::string_view key, const std::string& parent_kind) {
  const bool mapping = o.node(node).kind == OutlineNode::kMapping;
  if (!mapping) return {};
  if (parent_kind == "elements") {
    const std::string type = o.scalar_of(node, "type");
    return element_kind(type.empty() ? key : std::string_view(type));
  }
  if (key == "elements") {
    const std::string type = o.scalar_of(node, "type");
    return type.empty() ? "elements" : element_kind(type);
  }
  if (parent_kind == "body" && key == "links") return "links";
  if (parent_kind == "links")
    return key == "SubBody" || key == "ContinuousTrack" ? "link:" + std::string(key) : link_kind(o, node);
  if (parent_kind == "element:Shape" && key == "geometry") {
    const std::string type = o.scalar_of(node, "type");
    return table_node("geometry:" + type) ? "geometry:" + type : "geometry";
  }
  if (parent_kind == "element:Shape" && key == "appearance") return "appearance";
  if (parent_kind == "appearance" && (key == "material" || key == "texture")) return std::string(key);
  if ((parent_kind == "element:Resource" || parent_kind == "geometry:Resource") && key == "metadata") return "metadata";
  if (parent_kind == "element:Visual" && key == "shape") return "element:Shape";
  if (parent_kind == "element:Visual" && key == "resource") return "element:Resource";
  return {};
}

std::string node_kind_at(const Outline& o, int node, int depth) {
  if (node < 0 || depth > 400) return {};
  if (node == o.root()) return o.node(node).kind == OutlineNode::kMapping ? "body" : "";
  const int parent = o.node(node).parent;
  if (parent < 0) return {};
  const OutlineNode& p = o.node(parent);
  if (p.kind == OutlineNode::kSequence) {
    if (o.node(node).kind != OutlineNode::kMapping) return {};
    const OutlineEntry* holder = o.entry_of(parent);
    if (!holder) return {};
    const int owner = p.parent;
    if (holder->key == "links" && owner == o.root()) return link_kind(o, node);
    if ((holder->key == "extra_joints" || holder->key == "extraJoints") && owner == o.root()) return "extra_joint";
    if (holder->key == "elements") return element_kind(o.scalar_of(node, "type"));
    return {};
  }
  if (p.kind != OutlineNode::kMapping) return {};
  const OutlineEntry* entry = o.entry_of(node);
  if (!entry) return {};
  return kind_under_key(o, node, entry->key, node_kind_at(o, parent, depth + 1));
}

}  // namespace

std::string element_kind(std::string_view type) {
  if (type == "Shape") return "element:Shape";
  if (type == "Transform" || type == "Group" || type == "Node") return "element:Transform";
  if (type == "RigidBody") return "element:RigidBody";
  if (type == "Visual" || type == "Collision") return "element:Visual";
  if (type == "Resource") return "element:Resource";
  const auto& devices = device_type_names();
  if (std::find(devices.begin(), devices.end(), type) == devices.end()) return {};
  // Camera's other spellings read the same keys (body-format-spec §10.2).
  if (type == "CameraDevice") return "device:Camera";
  const std::string specific = "device:" + std::string(type);
  if (table_node(specific)) return specific;
  return "device";
  return {};
}

const BodyNode* table_node(std::string_view kind) { return find_body_node(kind); }

bool names_a_link(std::string_view kind, std::string_view key) {
  if (key == "parent") return is_link_kind(kind);
  if (key == "root_link" || key == "rootLink") return kind == "body";
  if (key == "link1_name" || key == "link2_name" || key == "link1Name" || key == "link2Name")
    return kind == "extra_joint";
  return false;
}

std::string node_kind(const Outline& outline, int node) { return node_kind_at(outline, node, 0); }

AngleMode angle_mode(const Outline& o) {
  AngleMode mode;
  std::string version = o.scalar_of(o.root(), "format_version");
  if (version.empty()) version = o.scalar_of(o.root(), "formatVersion");
  std::string unit = o.scalar_of(o.root(), "angle_unit");
  if (unit.empty()) unit = o.scalar_of(o.root(), "angleUnit");
  // The loader reads the version as strtod does (body-format-spec §1.2): "1.0x" is 1.0.
  const double v = version.empty() ? 2.0 : std::strtod(version.c_str(), nullptr);
  const std::string format = "format " + (version.empty() ? std::string("(no format_version)") : version);
  if (unit == "radian") {
    if (v >= 2.0) {
      mode.refused = true;
      mode.why = format + ", angle_unit: radian, which the loader refuses";
    } else {
      mode.degrees = false;
      mode.why = format + ", angle_unit: radian";
    }
  } else {
    mode.why = format + (unit.empty() ? std::string(", degrees by default") : ", angle_unit: " + unit);
  }
  return mode;
}

std::string angle_unit_word(const AngleMode& mode) {
  if (mode.refused) return "angle";
  return mode.degrees ? "degree" : "radian";
}

bool reads_as_angle(const Outline& o, int scalar, const BodyKey& key, int mapping, std::string& why) {
  switch (key.angle) {
    case AngleRule::kNone: why = "not an angle"; return false;
    case AngleRule::kAngle: return true;
    case AngleRule::kAngleIfRevolute: {
      std::string type = o.scalar_of(mapping, "joint_type");
      if (type.empty()) type = o.scalar_of(mapping, "jointType");
      if (type == "revolute") return true;
      why = "an angle only on a revolute joint; this joint is " + (type.empty() ? std::string("fixed") : type);
      return false;
    }
    case AngleRule::kAxisAngle: {
      // The 4th number of each [x, y, z, angle] (a flat list: of each quadruple).
      const int seq = o.node(scalar).parent;
      if (seq < 0 || o.node(seq).kind != OutlineNode::kSequence) {
        why = "not a number of an axis-angle list";
        return false;
      }
      const auto& items = o.node(seq).items;
      const auto at = std::find(items.begin(), items.end(), scalar) - items.begin();
      if (at % 4 == 3) return true;
      why = "an axis component (the angle is the 4th number)";
      return false;
    }
  }
  return false;
}

}  // namespace bodyfmt::lsp
