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

namespace {

/// Transforms the vertices, normals and triangles of `mesh` from the given indices on, by an
/// Affine3d or by a linear part alone (a Matrix3d), which adds no translation (not even the
/// zero that turns a -0 coordinate into 0).
template <typename Transform>
void transform_tail(TriangleMesh& mesh, const Transform& transform, const Eigen::Matrix3d& linear,
                    std::size_t first_vertex, std::size_t first_normal, std::size_t first_triangle) {
  for (std::size_t i = first_vertex; i < mesh.vertices.size(); ++i) mesh.vertices[i] = transform * mesh.vertices[i];
  if (first_normal < mesh.normals.size()) {
    const Eigen::Matrix3d normals = normal_matrix(linear);
    for (std::size_t i = first_normal; i < mesh.normals.size(); ++i) {
      const Eigen::Vector3d m = normals * mesh.normals[i];
      const double norm = m.norm();
      mesh.normals[i] = norm > 0 ? Eigen::Vector3d(m / norm) : Eigen::Vector3d::Zero();
    }
  }
  // A mirroring transform (negative determinant, e.g. a negative `scale` component) turns
  // counter-clockwise triangles clockwise; swapping two corners keeps them facing outward.
  if (linear.determinant() < 0)
    for (std::size_t i = first_triangle; i < mesh.triangles.size(); ++i)
      std::swap(mesh.triangles[i][1], mesh.triangles[i][2]);
}

}  // namespace

Eigen::Matrix3d normal_matrix(const Eigen::Matrix3d& linear) {
  // The cofactor alone would flip normals under a mirror, hence the inverse transpose whenever
  // it exists.
  if (linear.determinant() != 0) return linear.inverse().transpose();
  Eigen::Matrix3d cofactor;
  cofactor.col(0) = linear.col(1).cross(linear.col(2));
  cofactor.col(1) = linear.col(2).cross(linear.col(0));
  cofactor.col(2) = linear.col(0).cross(linear.col(1));
  return cofactor;
}

void transform_mesh(TriangleMesh& mesh, const Eigen::Affine3d& transform) {
  transform_tail(mesh, transform, transform.linear(), 0, 0, 0);
}

void transform_mesh(TriangleMesh& mesh, const Eigen::Matrix3d& linear) {
  transform_tail(mesh, linear, linear, 0, 0, 0);
}

void append_mesh(TriangleMesh& mesh, const TriangleMesh& other, const Eigen::Affine3d& transform) {
  const bool mesh_was_empty = mesh.vertices.empty();
  const std::size_t first_vertex = mesh.vertices.size();
  const std::size_t first_triangle = mesh.triangles.size();
  const int offset = static_cast<int>(first_vertex);

  // Per-vertex attributes stay only if both sides have them (TriangleMesh requires them to be
  // either complete or absent); an empty target adopts whatever `other` has.
  const bool keep_normals = (mesh_was_empty || mesh.normals.size() == mesh.vertices.size()) && !other.normals.empty() &&
                            other.normals.size() == other.vertices.size();
  const bool keep_tex_coords = (mesh_was_empty || mesh.tex_coords.size() == mesh.vertices.size()) &&
                               !other.tex_coords.empty() && other.tex_coords.size() == other.vertices.size();

  mesh.vertices.insert(mesh.vertices.end(), other.vertices.begin(), other.vertices.end());
  if (keep_normals)
    mesh.normals.insert(mesh.normals.end(), other.normals.begin(), other.normals.end());
  else
    mesh.normals.clear();
  if (keep_tex_coords)
    mesh.tex_coords.insert(mesh.tex_coords.end(), other.tex_coords.begin(), other.tex_coords.end());
  else
    mesh.tex_coords.clear();
  mesh.triangles.reserve(mesh.triangles.size() + other.triangles.size());
  for (const auto& t : other.triangles) mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  transform_tail(mesh, transform, transform.linear(), first_vertex, keep_normals ? first_vertex : mesh.normals.size(),
                 first_triangle);
}

}  // namespace bodyfmt
