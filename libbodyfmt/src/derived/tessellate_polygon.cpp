// Polygon triangulation for IndexedFaceSet faces and Extrusion caps (body-format-spec §9).
// Choreonoid uses its own Triangulator (ear clipping on the polygon); this is the same idea,
// done on the projection onto the polygon's best-fit plane so that slightly non-planar faces
// and faces in any orientation work.

#include <bodyfmt/tessellate.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace bodyfmt {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

bool triangulate_polygon(const std::vector<Eigen::Vector3d>& vertices,
                         const std::vector<int>& polygon,
                         std::vector<std::array<int, 3>>& triangles) {
  // Drop consecutive repeats (same index or same position, wrapping around): they add no
  // area and would make zero-length edges that break the convexity test.
  std::vector<int> ids;
  ids.reserve(polygon.size());
  for (int index : polygon) {
    const Eigen::Vector3d& p = vertices[static_cast<std::size_t>(index)];
    if (!ids.empty() && (ids.back() == index || vertices[static_cast<std::size_t>(ids.back())] == p))
      continue;
    ids.push_back(index);
  }
  while (ids.size() > 1 && (ids.front() == ids.back() ||
                            vertices[static_cast<std::size_t>(ids.front())] ==
                                vertices[static_cast<std::size_t>(ids.back())])) {
    ids.pop_back();
  }
  const std::size_t n = ids.size();
  if (n < 3) return false;

  auto at = [&](std::size_t k) -> const Eigen::Vector3d& {
    return vertices[static_cast<std::size_t>(ids[k])];
  };

  // Newell's normal: twice the vector area of the polygon, robust for non-planar and
  // non-convex polygons. Coordinates relative to the centroid keep it accurate far from the
  // origin.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < n; ++k) centroid += at(k);
  centroid /= static_cast<double>(n);
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double extent = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d a = at(k) - centroid;
    const Eigen::Vector3d b = at((k + 1) % n) - centroid;
    normal += a.cross(b);
    extent = std::max(extent, a.cwiseAbs().maxCoeff());
  }
  if (!std::isfinite(normal.norm()) || !(extent > 0)) return false;
  const double area_tolerance = 1e-12 * extent * extent;
  if (normal.norm() <= area_tolerance) return false;
  normal.normalize();

  // In-plane basis (u, v) with u x v = normal: the projected polygon is counter-clockwise.
  Eigen::Vector3d u = normal.unitOrthogonal();
  Eigen::Vector3d v = normal.cross(u);
  std::vector<Eigen::Vector2d> p(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d d = at(k) - centroid;
    p[k] = Eigen::Vector2d(d.dot(u), d.dot(v));
  }

  std::vector<std::array<int, 3>> result;
  result.reserve(n - 2);
  std::vector<std::size_t> remaining(n);
  for (std::size_t k = 0; k < n; ++k) remaining[k] = k;

  auto inside_or_on = [&](const Eigen::Vector2d& q, std::size_t a, std::size_t b, std::size_t c) {
    return cross2(p[b] - p[a], q - p[a]) >= -area_tolerance &&
           cross2(p[c] - p[b], q - p[b]) >= -area_tolerance &&
           cross2(p[a] - p[c], q - p[c]) >= -area_tolerance;
  };
  auto is_ear = [&](std::size_t m, std::size_t k) {
    const std::size_t a = remaining[(k + m - 1) % m];
    const std::size_t b = remaining[k];
    const std::size_t c = remaining[(k + 1) % m];
    if (cross2(p[b] - p[a], p[c] - p[b]) <= area_tolerance) return false;  // reflex or flat
    for (std::size_t r : remaining) {
      if (r == a || r == b || r == c) continue;
      // A vertex at the same place as a corner (bridged holes, touching polygons) does not
      // block the ear.
      if (p[r] == p[a] || p[r] == p[b] || p[r] == p[c]) continue;
      if (inside_or_on(p[r], a, b, c)) return false;
    }
    return true;
  };

  // Every pass removes one vertex, so this terminates after n - 3 passes at most.
  while (remaining.size() > 3) {
    const std::size_t m = remaining.size();
    std::size_t clip = m;
    for (std::size_t k = 0; k < m; ++k) {
      if (is_ear(m, k)) {
        clip = k;
        break;
      }
    }
    bool emit = true;
    if (clip == m) {
      // No ear: the polygon self-intersects or is numerically flat somewhere. Drop a flat
      // vertex if there is one (it adds no area); otherwise clip the most convex corner.
      double best = -std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < m; ++k) {
        const std::size_t a = remaining[(k + m - 1) % m];
        const std::size_t b = remaining[k];
        const std::size_t c = remaining[(k + 1) % m];
        const double turn = cross2(p[b] - p[a], p[c] - p[b]);
        if (std::abs(turn) <= area_tolerance) {
          clip = k;
          emit = false;
          break;
        }
        if (turn > best) {
          best = turn;
          clip = k;
        }
      }
    }
    const std::size_t a = remaining[(clip + m - 1) % m];
    const std::size_t b = remaining[clip];
    const std::size_t c = remaining[(clip + 1) % m];
    if (emit) result.push_back({ids[a], ids[b], ids[c]});
    remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(clip));
  }
  {
    const std::size_t a = remaining[0], b = remaining[1], c = remaining[2];
    if (std::abs(cross2(p[b] - p[a], p[c] - p[b])) > area_tolerance)
      result.push_back({ids[a], ids[b], ids[c]});
  }
  if (result.empty()) return false;
  triangles.insert(triangles.end(), result.begin(), result.end());
  return true;
}

}  // namespace bodyfmt
