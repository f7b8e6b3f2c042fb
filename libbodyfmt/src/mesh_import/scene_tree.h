#pragma once
/// The format-neutral scene tree every mesh reader produces (VRML97 and assimp alike), so
/// that node selection, re-centring (body-format-spec §9.4) and metadata are written once.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <vector>

namespace bodyfmt::mesh {

/// One node: a local transform, the mesh parts attached directly to it, and children.
/// Children are shared pointers because VRML `USE` instances the same subtree twice.
struct SceneNode {
  std::string name;
  Eigen::Affine3d transform = Eigen::Affine3d::Identity();  ///< may contain scale/shear
  std::vector<MeshPart> parts;                              ///< in this node's frame
  std::vector<std::shared_ptr<const SceneNode>> children;
};

using SceneTree = std::shared_ptr<const SceneNode>;

/// The first node named `name` in depth-first pre-order, with the accumulated transform of
/// its ancestors (excluding its own); nullptr when there is none.
const SceneNode* find_node(const SceneNode& root, const std::string& name, Eigen::Affine3d* ancestors_transform);

/// Flattens `node` (its own transform is applied after `parent`) into parts, applying the
/// transform to positions and normals.
void flatten(const SceneNode& node, const Eigen::Affine3d& parent, std::vector<MeshPart>& out);

/// Builds the parts of an asset: the whole tree, or the named node re-centred (§9.4: only the
/// linear part of the accumulated transform down to and including the node is kept), then the
/// metadata (length scale, Y-up rotation). The subtrees of `detached_nodes` (resolved by
/// name, other than the selected node) are left out. Returns false when the node is not found.
///
/// With `scene_bounds`, also computes the box Choreonoid's scene graph reports for the same
/// structure (MeshAsset::scene_bounds): mesh leaves give the tight box of their vertices,
/// groups the union of their children, and every transform the axis-aligned box of its
/// child box's 8 transformed corners. The re-centred node is one transform (the accumulated
/// linear part) above the node's contents, as Choreonoid's StdSceneReader leaves it; the
/// metadata is one more transform on top.
bool extract_parts(const SceneNode& root, const std::string& node_name, double length_scale, bool y_up,
                   std::vector<MeshPart>& out, const std::vector<std::string>& detached_nodes = {},
                   BoundingBox* scene_bounds = nullptr);

/// The axis-aligned box of the 8 transformed corners of `box` (Choreonoid's
/// BoundingBox::transform); empty stays empty.
BoundingBox transform_box(const BoundingBox& box, const Eigen::Affine3d& transform);

/// The rotation used for `upper_axis: Y`: mesh +Y -> +Z, +X -> +Y, +Z -> +X.
Eigen::Matrix3d y_up_rotation();

}  // namespace bodyfmt::mesh
