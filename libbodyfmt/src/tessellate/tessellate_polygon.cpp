// Polygon triangulation for IndexedFaceSet faces and Extrusion caps (body-format-spec §9).
// Choreonoid uses its own Triangulator (ear clipping on the polygon); this is the same idea,
// done on the projection onto the polygon's best-fit plane so that slightly non-planar faces
// and faces in any orientation work.

#include <bodyfmt/tessellate.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

namespace bodyfmt {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The polygon's indices without consecutive repeats (same index or same position, wrapping
/// around): they add no area and would make zero-length edges that break the convexity test.
std::vector<int> distinct_corners(const std::vector<Eigen::Vector3d>& vertices, const std::vector<int>& polygon) {
  auto at = [&](int index) -> const Eigen::Vector3d& { return vertices[static_cast<std::size_t>(index)]; };
  std::vector<int> ids;
  ids.reserve(polygon.size());
  for (int index : polygon) {
    if (!ids.empty() && (ids.back() == index || at(ids.back()) == at(index))) continue;
    ids.push_back(index);
  }
  while (ids.size() > 1 && (ids.front() == ids.back() || at(ids.front()) == at(ids.back()))) ids.pop_back();
  return ids;
}

/// The corners projected onto the polygon's best-fit plane, counter-clockwise, with the area
/// below which a corner or triangle counts as flat.
struct PlanarPolygon {
  std::vector<Eigen::Vector2d> p;
  double area_tolerance = 0;
};

std::optional<PlanarPolygon> project_to_plane(const std::vector<Eigen::Vector3d>& vertices,
                                              const std::vector<int>& ids) {
  const std::size_t n = ids.size();
  auto at = [&](std::size_t k) -> const Eigen::Vector3d& { return vertices[static_cast<std::size_t>(ids[k])]; };
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
  if (!std::isfinite(normal.norm()) || !(extent > 0)) return std::nullopt;
  PlanarPolygon planar;
  planar.area_tolerance = 1e-12 * extent * extent;
  if (normal.norm() <= planar.area_tolerance) return std::nullopt;
  normal.normalize();
  // In-plane basis (u, v) with u x v = normal: the projected polygon is counter-clockwise.
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.cross(u);
  planar.p.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d d = at(k) - centroid;
    planar.p[k] = Eigen::Vector2d(d.dot(u), d.dot(v));
  }
  return planar;
}

/// Ear clipping over the corners still in the polygon (positions into PlanarPolygon::p).
class EarClipper {
 public:
  explicit EarClipper(const PlanarPolygon& polygon)
      : p_(polygon.p), tolerance_(polygon.area_tolerance), large_(polygon.p.size() > kSmallPolygon) {
    remaining_.resize(p_.size());
    for (std::size_t k = 0; k < remaining_.size(); ++k) remaining_[k] = k;
  }

  /// Triangles as positions into the corners. Every pass removes one corner, so this ends
  /// after n - 3 passes at most.
  std::vector<std::array<std::size_t, 3>> run() {
    std::vector<std::array<std::size_t, 3>> result;
    result.reserve(p_.size() - 2);
    while (remaining_.size() > 3) {
      bool emit = true;
      const std::size_t clip = next_clip(emit);
      if (work_ > kWorkBudget) {
        over_budget_ = true;
        return {};
      }
      if (emit) result.push_back(corner(clip));
      remaining_.erase(remaining_.begin() + static_cast<std::ptrdiff_t>(clip));
      // The corner before the clipped one changed: look for the next ear there.
      start_ = clip == 0 ? 0 : clip - 1;
    }
    const std::array<std::size_t, 3> last = {remaining_[0], remaining_[1], remaining_[2]};  // = corner(1)
    if (std::abs(turn(1)) > tolerance_) result.push_back(last);
    return result;
  }

 private:
  /// The corner at position k of the remaining ones, with its two neighbours.
  std::array<std::size_t, 3> corner(std::size_t k) const {
    const std::size_t m = remaining_.size();
    return {remaining_[(k + m - 1) % m], remaining_[k], remaining_[(k + 1) % m]};
  }
  double turn(std::size_t k) const {
    const auto [a, b, c] = corner(k);
    return cross2(p_[b] - p_[a], p_[c] - p_[b]);
  }
  bool inside_or_on(const Eigen::Vector2d& q, std::size_t a, std::size_t b, std::size_t c) const {
    return cross2(p_[b] - p_[a], q - p_[a]) >= -tolerance_ && cross2(p_[c] - p_[b], q - p_[b]) >= -tolerance_ &&
           cross2(p_[a] - p_[c], q - p_[c]) >= -tolerance_;
  }
  bool is_ear(std::size_t k) const {
    if (turn(k) <= tolerance_) return false;  // reflex or flat
    work_ += remaining_.size();
    const auto [a, b, c] = corner(k);
    for (std::size_t r : remaining_) {
      if (r == a || r == b || r == c) continue;
      // A vertex at the same place as a corner (bridged holes, touching polygons) does not
      // block the ear.
      if (p_[r] == p_[a] || p_[r] == p_[b] || p_[r] == p_[c]) continue;
      if (inside_or_on(p_[r], a, b, c)) return false;
    }
    return true;
  }
  /// The first ear; without one (the polygon self-intersects or is numerically flat
  /// somewhere), a flat corner, which is dropped without a triangle (`emit` false), or else
  /// the most convex corner.
  std::size_t next_clip(bool& emit) const {
    const std::size_t m = remaining_.size();
    // A small polygon is searched from its first corner every time (the triangulation every
    // existing export was made with); a large one from where the last ear was cut, which
    // finds the next ear at once on convex runs and keeps the work near n² instead of n³.
    const std::size_t start = large_ ? std::min(start_, m - 1) : 0;
    for (std::size_t step = 0; step < m; ++step) {
      const std::size_t k = (start + step) % m;
      if (is_ear(k)) return k;
    }
    double best = -std::numeric_limits<double>::infinity();
    std::size_t clip = m;
    for (std::size_t k = 0; k < m; ++k) {
      const double t = turn(k);
      if (std::abs(t) <= tolerance_) {
        emit = false;
        return k;
      }
      if (t > best) {
        best = t;
        clip = k;
      }
    }
    return clip;
  }

  static constexpr std::size_t kSmallPolygon = 64;
  /// Point-in-triangle tests one polygon may take (a few seconds at most); a self-intersecting
  /// polygon of thousands of corners, which has few or no ears, would otherwise take minutes.
  static constexpr std::size_t kWorkBudget = 400'000'000;

  const std::vector<Eigen::Vector2d>& p_;
  double tolerance_;
  bool large_;
  std::vector<std::size_t> remaining_;
  std::size_t start_ = 0;
  mutable std::size_t work_ = 0;

 public:
  bool over_budget() const { return over_budget_; }

 private:
  bool over_budget_ = false;
};

}  // namespace

bool triangulate_polygon(const std::vector<Eigen::Vector3d>& vertices, const std::vector<int>& polygon,
                         std::vector<std::array<int, 3>>& triangles, bool* over_budget) {
  if (over_budget) *over_budget = false;
  const std::vector<int> ids = distinct_corners(vertices, polygon);
  if (ids.size() < 3) return false;
  const std::optional<PlanarPolygon> planar = project_to_plane(vertices, ids);
  if (!planar) return false;
  EarClipper clipper(*planar);
  const std::vector<std::array<std::size_t, 3>> clipped = clipper.run();
  if (over_budget) *over_budget = clipper.over_budget();
  if (clipped.empty()) return false;
  for (const auto& [a, b, c] : clipped) triangles.push_back({ids[a], ids[b], ids[c]});
  return true;
}

}  // namespace bodyfmt
