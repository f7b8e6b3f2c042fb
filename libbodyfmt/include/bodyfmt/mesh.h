#pragma once
/// Triangle meshes: what the tessellator and the mesh importers produce, and what the
/// exporters and the dynamics checker consume.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>

#include <Eigen/Geometry>

#include <array>
#include <optional>
#include <string>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// Surface material in VRML97 terms, as Choreonoid reads it (body-format-spec §8.7).
struct Material {
  double ambient_intensity = 1.0;
  Eigen::Vector3d diffuse_color{1, 1, 1};
  Eigen::Vector3d emissive_color{0, 0, 0};
  Eigen::Vector3d specular_color{0, 0, 0};
  double specular_exponent = 25.0;
  double transparency = 0.0;  ///< 0 = opaque, 1 = invisible (alpha = 1 - transparency)
  /// Where a body file wrote the emissive colour (its key), for an exporter that cannot
  /// write one; unknown when the colour comes from a mesh file or was not written. Not part
  /// of the material's value: == ignores it.
  SourceLocation emissive_source;

  friend bool operator==(const Material& a, const Material& b) {
    return a.ambient_intensity == b.ambient_intensity && a.diffuse_color == b.diffuse_color &&
           a.emissive_color == b.emissive_color && a.specular_color == b.specular_color &&
           a.specular_exponent == b.specular_exponent && a.transparency == b.transparency;
  }
};

/// An indexed triangle mesh in metres. Triangles are counter-clockwise seen from outside.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  /// Optional per-vertex normals (same size as vertices) or empty.
  std::vector<Eigen::Vector3d> normals;
  /// Optional per-vertex texture coordinates (same size as vertices) or empty.
  std::vector<Eigen::Vector2d> tex_coords;

  bool empty() const { return triangles.empty(); }
};

/// Axis-aligned bounding box; empty until a point is added.
struct BoundingBox {
  Eigen::Vector3d min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};
  Eigen::Vector3d max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                      -std::numeric_limits<double>::infinity()};

  bool empty() const { return !(min.x() <= max.x()); }
  void add(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void add(const BoundingBox& other) {
    if (!other.empty()) {
      add(other.min);
      add(other.max);
    }
  }
};

BoundingBox bounding_box(const TriangleMesh& mesh);
BoundingBox bounding_box(const TriangleMesh& mesh, const Eigen::Affine3d& transform);

/// Signed volume by the divergence theorem; positive for a closed, outward-oriented mesh.
double signed_volume(const TriangleMesh& mesh);

/// What normals map with under the linear part `linear` of a transform: its inverse transpose,
/// which keeps them perpendicular to the surface under non-uniform scale; where `linear` is
/// singular (a zero scale), the cofactor matrix, whose columns still give the limiting
/// directions instead of the infinities of an inverse.
Eigen::Matrix3d normal_matrix(const Eigen::Matrix3d& linear);

/// The one way a mesh is transformed: vertices by `transform`, normals by normal_matrix() and
/// made unit (zero where a zero scale flattened them), and under a mirror (negative
/// determinant) the winding swapped so that triangles still face outward.
void transform_mesh(TriangleMesh& mesh, const Eigen::Affine3d& transform);
/// The same by a linear part alone (shear or mirror baked into the vertices).
void transform_mesh(TriangleMesh& mesh, const Eigen::Matrix3d& linear);

/// Appends `other`, transformed as transform_mesh() does, to `mesh`.
void append_mesh(TriangleMesh& mesh, const TriangleMesh& other,
                 const Eigen::Affine3d& transform = Eigen::Affine3d::Identity());

}  // namespace bodyfmt
#pragma GCC visibility pop
