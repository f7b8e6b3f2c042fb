#include <bodyfmt/mesh.h>

#include <cstddef>

namespace bodyfmt {

namespace {

bool valid_triangle(const std::array<int, 3>& t, std::size_t num_vertices) {
  for (int i : t) {
    if (i < 0 || static_cast<std::size_t>(i) >= num_vertices) return false;
  }
  return true;
}

}  // namespace

// Every vertex counts, referenced by a triangle or not, as in Choreonoid's
// SgMesh::updateBoundingBox(): the box describes the vertex array.
BoundingBox bounding_box(const TriangleMesh& mesh) {
  BoundingBox box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.add(v);
  return box;
}

// Transforming the vertices (not the 8 corners of the local box) gives the tight box of the
// transformed mesh, which is what exporters and the collision checks need.
BoundingBox bounding_box(const TriangleMesh& mesh, const Eigen::Affine3d& transform) {
  BoundingBox box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.add(transform * v);
  return box;
}

// Divergence theorem with F(x) = x / 3: each triangle contributes the signed volume of the
// tetrahedron it spans with the origin. Triangles with out-of-range indices are skipped so
// that a malformed mesh never makes this read out of bounds.
double signed_volume(const TriangleMesh& mesh) {
  double six_volume = 0;
  for (const auto& t : mesh.triangles) {
    if (!valid_triangle(t, mesh.vertices.size())) continue;
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

void append_mesh(TriangleMesh& mesh, const TriangleMesh& other, const Eigen::Affine3d& transform) {
  const bool mesh_was_empty = mesh.vertices.empty();
  const int offset = static_cast<int>(mesh.vertices.size());
  const Eigen::Matrix3d linear = transform.linear();

  // Per-vertex attributes stay only if both sides have them (TriangleMesh requires them to be
  // either complete or absent); an empty target adopts whatever `other` has.
  const bool keep_normals = (mesh_was_empty || mesh.normals.size() == mesh.vertices.size()) && !other.normals.empty() &&
                            other.normals.size() == other.vertices.size();
  const bool keep_tex_coords = (mesh_was_empty || mesh.tex_coords.size() == mesh.vertices.size()) &&
                               !other.tex_coords.empty() && other.tex_coords.size() == other.vertices.size();

  mesh.vertices.reserve(mesh.vertices.size() + other.vertices.size());
  for (const Eigen::Vector3d& v : other.vertices) mesh.vertices.push_back(transform * v);

  if (keep_normals) {
    // Normals are covectors: they map with the inverse transpose of the linear part, which
    // keeps them perpendicular to the surface under non-uniform scale (spec §4.4 allows a
    // `scale` in the transform stack). A singular linear part (zero scale) has no inverse;
    // then the cofactor matrix (det * inverse transpose, columns a1 x a2, a2 x a0, a0 x a1)
    // still gives the limiting directions. (The cofactor alone would flip normals under a
    // mirror, hence the inverse transpose whenever it exists.)
    const double det = linear.determinant();
    Eigen::Matrix3d normal_matrix;
    if (det != 0) {
      normal_matrix = linear.inverse().transpose();
    } else {
      normal_matrix.col(0) = linear.col(1).cross(linear.col(2));
      normal_matrix.col(1) = linear.col(2).cross(linear.col(0));
      normal_matrix.col(2) = linear.col(0).cross(linear.col(1));
    }
    mesh.normals.reserve(mesh.vertices.size());
    for (const Eigen::Vector3d& n : other.normals) {
      Eigen::Vector3d m = normal_matrix * n;
      const double norm = m.norm();
      mesh.normals.push_back(norm > 0 ? Eigen::Vector3d(m / norm) : Eigen::Vector3d::Zero());
    }
  } else {
    mesh.normals.clear();
  }

  if (keep_tex_coords) {
    mesh.tex_coords.insert(mesh.tex_coords.end(), other.tex_coords.begin(), other.tex_coords.end());
  } else {
    mesh.tex_coords.clear();
  }

  // A mirroring transform (negative determinant, e.g. a negative `scale` component) turns
  // counter-clockwise triangles clockwise; swapping two corners keeps them facing outward.
  const bool mirrored = linear.determinant() < 0;
  mesh.triangles.reserve(mesh.triangles.size() + other.triangles.size());
  for (const auto& t : other.triangles) {
    std::array<int, 3> u{t[0] + offset, t[1] + offset, t[2] + offset};
    if (mirrored) std::swap(u[1], u[2]);
    mesh.triangles.push_back(u);
  }
}

}  // namespace bodyfmt
