// Per-vertex normals with VRML97 creaseAngle semantics (body-format-spec §9: IndexedFaceSet,
// Extrusion and ElevationGrid carry a crease_angle; Choreonoid's MeshFilter generates normals
// the same way when none are given).

#include <bodyfmt/angles.h>
#include <bodyfmt/tessellate.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>

namespace bodyfmt {

TriangleMesh with_vertex_normals(const TriangleMesh& mesh, double crease_angle) {
  const std::size_t nv = mesh.vertices.size();
  const std::size_t nt = mesh.triangles.size();
  auto valid = [&](const std::array<int, 3>& t) {
    for (int i : t)
      if (i < 0 || static_cast<std::size_t>(i) >= nv) return false;
    return true;
  };

  // Which faces meet at a vertex. With texture coordinates, the vertices at one position are
  // taken together: a texture seam splits vertices that one smooth surface shares.
  const bool has_tex = mesh.tex_coords.size() == nv && nv > 0;
  std::vector<std::size_t> place(nv);
  if (has_tex) {
    std::map<std::array<double, 3>, std::size_t> first;
    for (std::size_t v = 0; v < nv; ++v) {
      const Eigen::Vector3d& p = mesh.vertices[v];
      place[v] = first.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, v).first->second;
    }
  } else {
    for (std::size_t v = 0; v < nv; ++v) place[v] = v;
  }

  // Area-weighted face normals (twice the area) and unit directions for the angle test.
  std::vector<Eigen::Vector3d> weighted(nt, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> unit(nt, Eigen::Vector3d::Zero());
  std::vector<std::vector<std::size_t>> faces_at(nv);
  for (std::size_t f = 0; f < nt; ++f) {
    const auto& t = mesh.triangles[f];
    if (!valid(t)) continue;
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    weighted[f] = (b - a).cross(c - a);
    const double norm = weighted[f].norm();
    if (norm > 0 && std::isfinite(norm)) unit[f] = weighted[f] / norm;
    for (int i : t) {
      auto& list = faces_at[place[static_cast<std::size_t>(i)]];
      if (list.empty() || list.back() != f) list.push_back(f);
    }
  }
  // Faces meeting at less than the crease angle are smoothed together; at exactly the crease
  // angle they are not, so that Choreonoid's pi/2 for cylinders keeps the cap edges sharp.
  // Coplanar faces always share normals (that is what crease angle 0, flat shading, means).
  const double cos_crease = std::cos(std::min(std::max(crease_angle, 0.0), kPi));
  const bool smooth_all = crease_angle >= kPi;
  auto smoothed_together = [&](std::size_t f, std::size_t g) {
    if (smooth_all || g == f) return true;
    const double c = unit[f].dot(unit[g]);
    return c >= 1 - 1e-12 || c > cos_crease + 1e-12;
  };

  TriangleMesh out;
  out.triangles.reserve(nt);
  for (const auto& t : mesh.triangles) {
    if (valid(t)) out.triangles.push_back(t);  // bad indices cannot be given a normal
  }
  // (original vertex, normal) -> new vertex; normals are compared exactly because corners
  // sharing the same set of smoothed faces compute bit-identical sums.
  std::vector<std::map<std::array<double, 3>, int>> split(nv);
  std::size_t out_index = 0;
  for (std::size_t f = 0; f < nt; ++f) {
    if (!valid(mesh.triangles[f])) continue;
    auto& t = out.triangles[out_index++];
    for (int& corner : t) {
      const std::size_t v = static_cast<std::size_t>(corner);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (std::size_t g : faces_at[place[v]]) {
        if (smoothed_together(f, g)) sum += weighted[g];
      }
      const double norm = sum.norm();
      const Eigen::Vector3d n = norm > 0 && std::isfinite(norm) ? Eigen::Vector3d(sum / norm) : Eigen::Vector3d::Zero();
      const std::array<double, 3> key{n.x(), n.y(), n.z()};
      auto [it, inserted] = split[v].emplace(key, static_cast<int>(out.vertices.size()));
      if (inserted) {
        out.vertices.push_back(mesh.vertices[v]);
        out.normals.push_back(n);
        if (has_tex) out.tex_coords.push_back(mesh.tex_coords[v]);
      }
      corner = it->second;
    }
  }
  return out;
}

}  // namespace bodyfmt
