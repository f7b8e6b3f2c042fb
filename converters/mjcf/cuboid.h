#pragma once
/// Whether a triangle mesh is exactly a rectangular box, for body2mjcf: MuJoCo 2.2.2 collides
/// a box with a plane at its corners, but a mesh at its deepest vertex and at most two hull
/// neighbours farther from it than 0.3 of the geom's bounding radius, so a mesh box resting on
/// a face narrower than that stands on a line and creeps. The same box written as a `box` geom
/// is the same geometry with the contact it needs.
#include <bodyfmt/mesh.h>

#include <Eigen/Geometry>

#include <optional>

namespace bodyfmt::mjcf {

/// Corners closer than this fraction of the mesh's bounding-box diagonal are one corner, and a
/// box edge may lean this far (as a distance along another edge) from square.
constexpr double kCuboidTolerance = 1e-6;

struct Cuboid {
  /// The box's frame in the mesh's frame: its centre, and its edges along the frame's axes,
  /// each axis chosen as the mesh axis it is closest to (an axis-aligned box has the identity).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d half_edges = Eigen::Vector3d::Zero();
};

/// The box `mesh` is, its vertices first multiplied by `scale` per axis, when the corners of its
/// triangles are exactly 8 points forming a cuboid (within kCuboidTolerance) and its triangles
/// lie on the box's faces and cover all six; otherwise none. Unused vertices do not count (a
/// mesh file holds only the triangles' corners).
std::optional<Cuboid> exact_cuboid(const TriangleMesh& mesh, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

}  // namespace bodyfmt::mjcf
