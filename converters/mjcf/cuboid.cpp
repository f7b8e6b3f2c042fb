#include "cuboid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace bodyfmt::mjcf {
namespace {

/// Whether point (u, v) of a face's unit square lies strictly inside the triangle a, b, c of
/// its corners (corner coordinates 0 or 1).
bool inside(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  auto side = [](const Eigen::Vector2d& o, const Eigen::Vector2d& s, const Eigen::Vector2d& q) {
    return (s.x() - o.x()) * (q.y() - o.y()) - (s.y() - o.y()) * (q.x() - o.x());
  };
  const double d1 = side(a, b, p), d2 = side(b, c, p), d3 = side(c, a, p);
  return (d1 > 0 && d2 > 0 && d3 > 0) || (d1 < 0 && d2 < 0 && d3 < 0);
}

}  // namespace

std::optional<Cuboid> exact_cuboid(const TriangleMesh& mesh, const Eigen::Vector3d& scale) {
  const int n = static_cast<int>(mesh.vertices.size());
  std::vector<int> used;
  std::vector<char> seen(mesh.vertices.size(), 0);
  for (const auto& triangle : mesh.triangles)
    for (int i : triangle) {
      if (i < 0 || i >= n) return std::nullopt;
      if (!seen[i]) {
        seen[i] = 1;
        used.push_back(i);
      }
    }
  if (used.size() < 8) return std::nullopt;
  BoundingBox bounds;
  for (int i : used) bounds.add(mesh.vertices[i].cwiseProduct(scale));
  const double tolerance = kCuboidTolerance * (bounds.max - bounds.min).norm();
  if (!(tolerance > 0) || !std::isfinite(tolerance)) return std::nullopt;

  // The distinct corners, and which one each vertex is.
  std::vector<Eigen::Vector3d> points;
  std::vector<int> corner_of(mesh.vertices.size(), -1);
  for (int i : used) {
    const Eigen::Vector3d p = mesh.vertices[i].cwiseProduct(scale);
    int found = -1;
    for (std::size_t k = 0; k < points.size() && found < 0; ++k)
      if ((points[k] - p).norm() <= tolerance) found = static_cast<int>(k);
    if (found < 0) {
      if (points.size() == 8) return std::nullopt;
      found = static_cast<int>(points.size());
      points.push_back(p);
    }
    corner_of[i] = found;
  }
  if (points.size() != 8) return std::nullopt;

  // Three edges from corner 0, square to each other, whose sums reach every other corner
  // exactly once: bits[k] is corner k's position along each edge (0 or 1).
  std::array<Eigen::Vector3d, 3> edges;
  std::array<std::array<int, 3>, 8> bits{};
  bool found = false;
  for (int a = 1; a < 8 && !found; ++a)
    for (int b = a + 1; b < 8 && !found; ++b)
      for (int c = b + 1; c < 8 && !found; ++c) {
        const std::array<Eigen::Vector3d, 3> e = {points[a] - points[0], points[b] - points[0], points[c] - points[0]};
        bool square = true;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            if (i != j && std::abs(e[i].dot(e[j].normalized())) > tolerance) square = false;
        if (!square) continue;
        std::array<bool, 8> taken{};
        bool all = true;
        for (int m = 0; m < 8 && all; ++m) {
          const Eigen::Vector3d q = points[0] + (m & 1) * e[0] + ((m >> 1) & 1) * e[1] + ((m >> 2) & 1) * e[2];
          int hit = -1;
          for (int k = 0; k < 8 && hit < 0; ++k)
            if (!taken[k] && (points[k] - q).norm() <= tolerance) hit = k;
          if (hit < 0) {
            all = false;
            break;
          }
          taken[hit] = true;
          bits[hit] = {m & 1, (m >> 1) & 1, (m >> 2) & 1};
        }
        if (!all) continue;
        edges = e;
        found = true;
      }
  if (!found) return std::nullopt;

  // Every triangle lies on a face, and the triangles of each face cover it: each of the four
  // quarters the face's diagonals cut it into has its centroid inside one of them.
  std::array<std::vector<std::array<Eigen::Vector2d, 3>>, 6> on_face;
  for (const auto& triangle : mesh.triangles) {
    bool placed = false;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        bool on = true;
        for (int i : triangle) on = on && bits[corner_of[i]][axis] == side;
        if (!on) continue;
        placed = true;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        std::array<Eigen::Vector2d, 3> flat;
        for (int k = 0; k < 3; ++k) {
          const auto& c = bits[corner_of[triangle[k]]];
          flat[k] = Eigen::Vector2d(c[u], c[v]);
        }
        on_face[2 * axis + side].push_back(flat);
      }
    if (!placed) return std::nullopt;  // through the inside: not only the box's surface
  }
  const std::array<Eigen::Vector2d, 4> quarters = {Eigen::Vector2d(0.5, 1.0 / 6), Eigen::Vector2d(5.0 / 6, 0.5),
                                                   Eigen::Vector2d(0.5, 5.0 / 6), Eigen::Vector2d(1.0 / 6, 0.5)};
  for (const auto& face : on_face)
    for (const Eigen::Vector2d& q : quarters)
      if (std::none_of(face.begin(), face.end(), [&](const auto& t) { return inside(q, t[0], t[1], t[2]); }))
        return std::nullopt;

  // The box's axes: each edge on the mesh axis it is closest to, pointing along it, as a
  // proper rotation (a box is symmetric under every flip of an edge).
  std::array<int, 3> order = {0, 1, 2}, best = order;
  double best_score = -1;
  do {
    double score = 0;
    for (int axis = 0; axis < 3; ++axis) score += std::abs(edges[order[axis]].normalized()[axis]);
    if (score > best_score + 1e-12) {
      best_score = score;
      best = order;
    }
  } while (std::next_permutation(order.begin(), order.end()));
  Eigen::Matrix3d R;
  Cuboid box;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d& e = edges[best[axis]];
    box.half_edges[axis] = e.norm() / 2;
    R.col(axis) = e.normalized() * (e[axis] < 0 ? -1.0 : 1.0);
  }
  // Square within the tolerance, made exactly orthonormal and proper.
  R.col(0).normalize();
  R.col(1) = (R.col(1) - R.col(1).dot(R.col(0)) * R.col(0)).normalized();
  R.col(2) = R.col(0).cross(R.col(1));
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centre += p;
  box.pose.linear() = R;
  box.pose.translation() = centre / 8;
  return box;
}

}  // namespace bodyfmt::mjcf
