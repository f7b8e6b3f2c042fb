#include "mesh_import/scene_tree.h"

#include <bodyfmt/mesh.h>

#include <set>

namespace bodyfmt::mesh {

namespace {

const SceneNode* find_node_rec(const SceneNode& node, const std::string& name, const Eigen::Affine3d& parent,
                               Eigen::Affine3d* ancestors) {
  if (node.name == name) {
    if (ancestors) *ancestors = parent;
    return &node;
  }
  const Eigen::Affine3d here = parent * node.transform;
  for (const auto& child : node.children) {
    if (const SceneNode* found = find_node_rec(*child, name, here, ancestors)) return found;
  }
  return nullptr;
}

}  // namespace

const SceneNode* find_node(const SceneNode& root, const std::string& name, Eigen::Affine3d* ancestors_transform) {
  return find_node_rec(root, name, Eigen::Affine3d::Identity(), ancestors_transform);
}

/// The node's parts and subtree under `here`, which replaces the node's own transform.
static void flatten_contents(const SceneNode& node, const Eigen::Affine3d& here, std::vector<MeshPart>& out,
                             const std::set<const SceneNode*>& skip) {
  for (const MeshPart& part : node.parts) {
    if (part.mesh.triangles.empty()) continue;
    MeshPart copy = part;
    transform_mesh(copy.mesh, here);
    out.push_back(std::move(copy));
  }
  for (const auto& child : node.children) {
    if (!skip.count(child.get())) flatten_contents(*child, here * child->transform, out, skip);
  }
}

/// The box of the node's parts and subtree in the node's own frame (its transform excluded).
static BoundingBox contents_box(const SceneNode& node, const std::set<const SceneNode*>& skip) {
  BoundingBox box;
  for (const MeshPart& part : node.parts) {
    if (!part.mesh.triangles.empty()) box.add(bounding_box(part.mesh));
  }
  for (const auto& child : node.children) {
    if (!skip.count(child.get())) box.add(transform_box(contents_box(*child, skip), child->transform));
  }
  return box;
}

BoundingBox transform_box(const BoundingBox& box, const Eigen::Affine3d& transform) {
  if (box.empty()) return box;
  BoundingBox out;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                                 (i & 4) ? box.max.z() : box.min.z());
    out.add(transform * corner);
  }
  return out;
}

void flatten(const SceneNode& node, const Eigen::Affine3d& parent, std::vector<MeshPart>& out) {
  flatten_contents(node, parent * node.transform, out, {});
}

Eigen::Matrix3d y_up_rotation() {
  Eigen::Matrix3d r;
  // Columns are the images of mesh X, Y, Z: X -> +Y, Y -> +Z, Z -> +X (body-format-spec §9.4).
  r << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  return r;
}

bool extract_parts(const SceneNode& root, const std::string& node_name, double length_scale, bool y_up,
                   std::vector<MeshPart>& out, const std::vector<std::string>& detached_nodes,
                   BoundingBox* scene_bounds) {
  Eigen::Affine3d start = Eigen::Affine3d::Identity();
  const SceneNode* node = &root;
  if (!node_name.empty()) {
    Eigen::Affine3d ancestors = Eigen::Affine3d::Identity();
    node = find_node(root, node_name, &ancestors);
    if (!node) return false;
    // §9.4 re-centring: the linear part of a product is the product of the linear parts, so
    // dropping every translation down to and including the node is keeping only the linear
    // part of the accumulated transform. The node's descendants keep their own transforms.
    start.linear() = (ancestors * node->transform).linear();
    start.translation().setZero();
  } else {
    start = root.transform;
  }
  Eigen::Affine3d metadata = Eigen::Affine3d::Identity();
  metadata.linear() = (y_up ? y_up_rotation() : Eigen::Matrix3d::Identity()) * length_scale;

  std::set<const SceneNode*> skip;
  for (const std::string& name : detached_nodes) {
    const SceneNode* detached = find_node(root, name, nullptr);
    if (detached && detached != node) skip.insert(detached);
  }
  flatten_contents(*node, metadata * start, out, skip);
  if (scene_bounds) {
    // Whole file: the root's own transform; a selected node: one transform holding the
    // accumulated linear part (StdSceneReader::adjustNodeCoordinate). Either way `start`.
    *scene_bounds = transform_box(transform_box(contents_box(*node, skip), start), metadata);
  }
  return true;
}

}  // namespace bodyfmt::mesh
