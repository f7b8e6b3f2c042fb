// Texture coordinates for tessellated geometry, by the conventions of Choreonoid's
// MeshGenerator (generateTextureCoordinateFor*) and VRML97 §6: see tessellate.h for the
// mapping of each geometry. Each triangle corner gets its coordinate first; vertices are then
// split wherever corners sharing a vertex disagree (box edges, the seam at -Z, caps, poles).
//
// The corners are found by the vertex layout the tessellator in tessellate.cpp produces (ring
// i, longitude j), not from the positions, so that no angle is recovered through atan2 and the
// seam falls exactly on the vertices at -Z.

#include "tessellate/tessellate_internal.h"

#include <bodyfmt/angles.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <tuple>

namespace bodyfmt::detail {

namespace {

using Corners = std::array<Eigen::Vector2d, 3>;
using CornerTexCoords = std::vector<Corners>;  // one per triangle

/// u of longitude j of n, where vertex j sits at angle 2 pi j / n from +X towards +Z: 0 at -Z
/// (j = 3n/4), growing through -X, +Z and +X. Computed as (3n/4 - j) / n with the numerator
/// exact, so the vertex at -Z gets exactly 0.
double longitude_u(int j, int n) {
  double numerator = 0.75 * n - j;
  if (numerator < 0) numerator += n;
  return numerator / n;
}

/// A triangle whose corners straddle the seam (u near 1 beside u near 0) takes the upper copy
/// of the small values, so that it does not stretch backwards over the whole image.
void unwrap_seam(Corners& c, const std::array<bool, 3>& on_ring) {
  double lo = 2, hi = -1;
  for (int k = 0; k < 3; ++k) {
    if (!on_ring[static_cast<std::size_t>(k)]) continue;
    lo = std::min(lo, c[static_cast<std::size_t>(k)].x());
    hi = std::max(hi, c[static_cast<std::size_t>(k)].x());
  }
  if (hi - lo <= 0.5) return;
  for (int k = 0; k < 3; ++k) {
    if (on_ring[static_cast<std::size_t>(k)] && c[static_cast<std::size_t>(k)].x() < 0.5)
      c[static_cast<std::size_t>(k)].x() += 1;
  }
}

/// A pole or apex corner (not on a ring) takes the mean u of the triangle's ring corners.
void centre_pole_u(Corners& c, const std::array<bool, 3>& on_ring) {
  double sum = 0;
  int count = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    if (on_ring[k]) {
      sum += c[k].x();
      ++count;
    }
  }
  if (count == 0) return;
  for (std::size_t k = 0; k < 3; ++k) {
    if (!on_ring[k]) c[k].x() = sum / count;
  }
}

CornerTexCoords box_tex_coords(const TriangleMesh& mesh) {
  // Corner signs of the eight box vertices as tessellate.cpp lays them out.
  static constexpr int kSign[8][3] = {{1, 1, 1},  {-1, 1, 1},  {-1, -1, 1},  {1, -1, 1},
                                      {1, 1, -1}, {-1, 1, -1}, {-1, -1, -1}, {1, -1, -1}};
  // Per face (triangles 2f, 2f + 1): the signed axes along which u and v grow, so that the
  // image stands upright seen from outside; the faces are +Z, +Y, -X, -Y, +X, -Z in
  // tessellate.cpp's order (as in Choreonoid's generateTextureCoordinateForBox).
  struct Axes {
    int u_axis, u_sign, v_axis, v_sign;
  };
  static constexpr Axes kFace[6] = {{0, 1, 1, 1}, {0, 1, 2, -1}, {2, 1, 1, 1},
                                    {0, 1, 2, 1}, {2, -1, 1, 1}, {0, -1, 1, 1}};
  CornerTexCoords out(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size() && t < 12; ++t) {
    const Axes& a = kFace[t / 2];
    for (std::size_t k = 0; k < 3; ++k) {
      const int* s = kSign[mesh.triangles[t][k]];
      out[t][k] = {(1 + a.u_sign * s[a.u_axis]) / 2.0, (1 + a.v_sign * s[a.v_axis]) / 2.0};
    }
  }
  return out;
}

/// Sphere and Capsule: rings of n vertices (ring r at index r * n, from the top down), then
/// the top and the bottom pole. A sphere's v is its latitude, 1 - (r + 1) / bands, as
/// Choreonoid's 1 - acos(y / radius) / pi; a capsule's (Choreonoid gives it none) is the height
/// above its bottom over its whole height, so the image is not squeezed on the cylinder part.
CornerTexCoords round_tex_coords(const TriangleMesh& mesh, int n, std::optional<int> sphere_bands) {
  const int ring_vertices = static_cast<int>(mesh.vertices.size()) - 2;
  const double bottom = mesh.vertices.back().y(), top = mesh.vertices[mesh.vertices.size() - 2].y();
  auto ring_v = [&](int v) {
    if (sphere_bands) return 1.0 - double(v / n + 1) / *sphere_bands;
    return (mesh.vertices[static_cast<std::size_t>(v)].y() - bottom) / (top - bottom);
  };
  CornerTexCoords out(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<bool, 3> on_ring{};
    for (std::size_t k = 0; k < 3; ++k) {
      const int v = mesh.triangles[t][k];
      on_ring[k] = v < ring_vertices;
      out[t][k] = {on_ring[k] ? longitude_u(v % n, n) : 0.0, on_ring[k] ? ring_v(v) : (v == ring_vertices ? 1.0 : 0.0)};
    }
    unwrap_seam(out[t], on_ring);
    centre_pole_u(out[t], on_ring);
  }
  return out;
}

/// The disc of a cap at circle angle 2 pi i / n; `top` mirrors v so that the image reads
/// upright seen from above, as Choreonoid maps it.
Eigen::Vector2d cap_tex_coord(int i, int n, bool top) {
  const double a = i * 2.0 * kPi / n;
  return {0.5 + 0.5 * std::cos(a), top ? 0.5 - 0.5 * std::sin(a) : 0.5 + 0.5 * std::sin(a)};
}

/// Cylinder: top ring 0..n-1, bottom ring n..2n-1, then the top and bottom cap centres.
CornerTexCoords cylinder_tex_coords(const TriangleMesh& mesh, int n) {
  const int top_center = 2 * n, bottom_center = 2 * n + 1;
  CornerTexCoords out(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const bool top_cap = std::count(tri.begin(), tri.end(), top_center) > 0;
    const bool bottom_cap = std::count(tri.begin(), tri.end(), bottom_center) > 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const int v = tri[k];
      if (top_cap || bottom_cap)
        out[t][k] = v >= 2 * n ? Eigen::Vector2d(0.5, 0.5) : cap_tex_coord(v % n, n, top_cap);
      else
        out[t][k] = {longitude_u(v % n, n), v < n ? 1.0 : 0.0};
    }
    if (!top_cap && !bottom_cap) unwrap_seam(out[t], {true, true, true});
  }
  return out;
}

/// Cone: base ring 0..n-1, the apex n, the base centre n + 1.
CornerTexCoords cone_tex_coords(const TriangleMesh& mesh, int n) {
  const int apex = n, bottom_center = n + 1;
  CornerTexCoords out(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const bool side = std::count(tri.begin(), tri.end(), apex) > 0;
    std::array<bool, 3> on_ring{};
    for (std::size_t k = 0; k < 3; ++k) {
      const int v = tri[k];
      on_ring[k] = v < n;
      if (side)
        out[t][k] = {on_ring[k] ? longitude_u(v, n) : 0.0, on_ring[k] ? 0.0 : 1.0};
      else
        out[t][k] = v == bottom_center ? Eigen::Vector2d(0.5, 0.5) : cap_tex_coord(v, n, false);
    }
    if (side) {
      unwrap_seam(out[t], on_ring);
      centre_pole_u(out[t], on_ring);
    }
  }
  return out;
}

/// ElevationGrid vertex (i, j) at index j * x_dimension + i.
CornerTexCoords elevation_grid_tex_coords(const TriangleMesh& mesh, const ElevationGrid& grid) {
  CornerTexCoords out(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const int v = mesh.triangles[t][k];
      out[t][k] = {double(v % grid.x_dimension) / (grid.x_dimension - 1),
                   double(v / grid.x_dimension) / (grid.z_dimension - 1)};
    }
  }
  return out;
}

/// Cumulative lengths along a polyline, from 0 at its first point, as fractions of the whole
/// (all 0 for a polyline of no length).
template <typename Point>
std::vector<double> length_fractions(const std::vector<Point>& points) {
  std::vector<double> at(points.size(), 0.0);
  for (std::size_t k = 1; k < points.size(); ++k) at[k] = at[k - 1] + (points[k] - points[k - 1]).norm();
  const double total = at.empty() ? 0.0 : at.back();
  for (double& a : at) a = total > 0 ? a / total : 0.0;
  return at;
}

/// Extrusion, laid out as tessellate_extrusion.cpp does: vertex (i, j) of spine point i and
/// cross-section point j at i * nc + j (closing points dropped), the side triangles first (two
/// per segment pair, spine-major), then the begin cap (row 0) and the end cap (last row).
/// Sides: u is the length along the cross-section, v the length along the spine, each as a
/// fraction of the whole (so a closed cross-section or spine ends at 1 on a seam). Caps: the
/// cross-section's bounding box stretched to the image, the end cap mirrored in u (as
/// Choreonoid's generateTextureCoordinateForExtrusion).
CornerTexCoords extrusion_tex_coords(const TriangleMesh& mesh, const Extrusion& e) {
  const bool spine_closed = e.spine.front() == e.spine.back();
  const bool cs_closed = e.cross_section.front() == e.cross_section.back();
  const int ns = static_cast<int>(e.spine.size()) - (spine_closed ? 1 : 0);
  const int nc = static_cast<int>(e.cross_section.size()) - (cs_closed ? 1 : 0);
  const std::size_t cs_segments = static_cast<std::size_t>(cs_closed ? nc : nc - 1);
  const std::size_t sides = 2 * static_cast<std::size_t>(spine_closed ? ns : ns - 1) * cs_segments;
  const std::vector<double> s = length_fractions(e.cross_section), t = length_fractions(e.spine);
  Eigen::Vector2d lo = e.cross_section.front(), hi = e.cross_section.front();
  for (const auto& c : e.cross_section) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const Eigen::Vector2d size = hi - lo;
  auto fraction = [](double x, double extent) { return extent > 0 ? x / extent : 0.0; };
  CornerTexCoords out(mesh.triangles.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (std::size_t k = 0; k < 3; ++k) {
      const int v = mesh.triangles[f][k];
      const int row = v / nc, col = v % nc;
      if (f < sides) {
        // Segment (i, j) spans rows i, i + 1 and columns j, j + 1 (wrapping to 0 on a closed
        // list, whose closing point carries the full length 1).
        const int i = static_cast<int>(f / (2 * cs_segments)), j = static_cast<int>(f % (2 * cs_segments) / 2);
        const std::size_t u_at = static_cast<std::size_t>(col == j ? j : j + 1);
        const std::size_t v_at = static_cast<std::size_t>(row == i ? i : i + 1);
        out[f][k] = {s[u_at], t[v_at]};
      } else {
        const Eigen::Vector2d& c = e.cross_section[static_cast<std::size_t>(col)];
        const double u = fraction(c.x() - lo.x(), size.x());
        out[f][k] = {row == 0 ? u : 1 - u, fraction(c.y() - lo.y(), size.y())};
      }
    }
  }
  return out;
}

/// VRML97's default for a face set without texCoord: the largest extent of the bounding box
/// of all points carries u from 0 to 1, the second largest v at the same scale (ties prefer
/// X, then Y, then Z).
std::vector<Eigen::Vector2d> default_tex_coords(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d size = hi - lo;
  std::array<int, 3> axes{0, 1, 2};
  std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return size[a] > size[b]; });
  const int s = axes[0], t = axes[1];
  const double scale = size[s] > 0 ? 1.0 / size[s] : 0.0;
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const auto& p : points) out.emplace_back((p[s] - lo[s]) * scale, (p[t] - lo[t]) * scale);
  return out;
}

/// IndexedFaceSet (`polygons` true: `faces` holds -1-terminated polygons) or TriangleMesh.
/// nullopt when an index does not reach a texture coordinate.
template <typename FaceList>
std::optional<CornerTexCoords> face_list_tex_coords(const TriangleMesh& mesh, const FaceList& g,
                                                    const std::vector<std::size_t>& origins, bool polygons) {
  CornerTexCoords out(mesh.triangles.size());
  if (origins.size() != mesh.triangles.size()) return std::nullopt;
  if (g.tex_coords.empty()) {
    const std::vector<Eigen::Vector2d> uv = default_tex_coords(g.vertices);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (std::size_t k = 0; k < 3; ++k) out[t][k] = uv[static_cast<std::size_t>(mesh.triangles[t][k])];
    return out;
  }
  const std::vector<int>& indices = g.tex_coord_indices.empty() ? g.faces : g.tex_coord_indices;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      // The corner's position in `faces`: the polygon's first index holding this vertex.
      std::size_t position = origins[t] + k;
      if (polygons) {
        position = origins[t];
        while (position < g.faces.size() && g.faces[position] != mesh.triangles[t][k] && g.faces[position] != -1)
          ++position;
        if (position >= g.faces.size() || g.faces[position] == -1) return std::nullopt;
      }
      if (position >= indices.size()) return std::nullopt;
      const int index = indices[position];
      if (index < 0 || static_cast<std::size_t>(index) >= g.tex_coords.size()) return std::nullopt;
      out[t][k] = g.tex_coords[static_cast<std::size_t>(index)];
    }
  }
  return out;
}

/// One vertex per distinct (vertex, texture coordinate) pair, in order of first use.
TriangleMesh split_by_corner(const TriangleMesh& mesh, const CornerTexCoords& corners) {
  TriangleMesh out;
  out.triangles.reserve(mesh.triangles.size());
  std::map<std::tuple<int, double, double>, int> index;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<int, 3> tri{};
    for (std::size_t k = 0; k < 3; ++k) {
      const int v = mesh.triangles[t][k];
      const Eigen::Vector2d& uv = corners[t][k];
      auto [it, inserted] = index.emplace(std::make_tuple(v, uv.x(), uv.y()), static_cast<int>(out.vertices.size()));
      if (inserted) {
        out.vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
        out.tex_coords.push_back(uv);
      }
      tri[k] = it->second;
    }
    out.triangles.push_back(tri);
  }
  return out;
}

}  // namespace

TriangleMesh with_tex_coords(const TriangleMesh& mesh, const Geometry& geometry, int n,
                             const std::vector<std::size_t>& origins) {
  std::optional<CornerTexCoords> corners;
  if (std::holds_alternative<Box>(geometry))
    corners = box_tex_coords(mesh);
  else if (std::holds_alternative<Sphere>(geometry))
    corners = round_tex_coords(mesh, n, n / 2);
  else if (std::holds_alternative<Capsule>(geometry))
    corners = round_tex_coords(mesh, n, std::nullopt);
  else if (std::holds_alternative<Cylinder>(geometry))
    corners = cylinder_tex_coords(mesh, n);
  else if (std::holds_alternative<Cone>(geometry))
    corners = cone_tex_coords(mesh, n);
  else if (const auto* extrusion = geometry_if<Extrusion>(geometry))
    corners = extrusion_tex_coords(mesh, *extrusion);
  else if (const auto* grid = geometry_if<ElevationGrid>(geometry))
    corners = elevation_grid_tex_coords(mesh, *grid);
  else if (const auto* face_set = geometry_if<IndexedFaceSet>(geometry))
    corners = face_list_tex_coords(mesh, *face_set, origins, true);
  else if (const auto* list = geometry_if<TriangleMeshGeometry>(geometry))
    corners = face_list_tex_coords(mesh, *list, origins, false);
  if (!corners) return mesh;
  return split_by_corner(mesh, *corners);
}

}  // namespace bodyfmt::detail
