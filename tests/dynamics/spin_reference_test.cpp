// The quasi-static references of the tank suite (spin_reference.h), on hand-made layouts:
// the T6 oracle value, convergence where the old damped Newton solve diverged, refusals that
// name their cause, and loads that never go negative.
#include <doctest/doctest.h>

#include <bodyfmt/dynamics/spin_reference.h>

#include <cmath>
#include <string>
#include <vector>

using namespace bodyfmt::dynamics;

namespace {

/// Four corners per track (x = ±0.22, y = ±0.05 about track centres ±half_spacing).
std::vector<Eigen::Vector3d> corners(double half_spacing, double x_shift_right = 0) {
  std::vector<Eigen::Vector3d> points;
  for (double side : {half_spacing, -half_spacing})
    for (double x : {-0.22, 0.22})
      for (double y : {-0.05, 0.05}) points.emplace_back(x + (side < 0 ? x_shift_right : 0), side + y, 0);
  return points;
}

/// Belt velocities for dq_L on the left (y > 0) and dq_R on the right, axes +Y (belt along −X).
std::vector<Eigen::Vector3d> belts(const std::vector<Eigen::Vector3d>& points, double left, double right) {
  std::vector<Eigen::Vector3d> belt;
  for (const auto& p : points) belt.emplace_back(p.y() > 0 ? -left : -right, 0, 0);
  return belt;
}

double residual_of(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& loads,
                   const std::vector<Eigen::Vector3d>& belt, const Eigen::Vector3d& x) {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  double total = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d s(x[0] - x[2] * points[i].y() + belt[i].x(), x[1] + x[2] * points[i].x() + belt[i].y());
    const Eigen::Vector2d f = -loads[i] * s.normalized();
    r += Eigen::Vector3d(f.x(), f.y(), points[i].x() * f.y() - points[i].y() * f.x());
    total += loads[i];
  }
  return r.norm() / total;
}

}  // namespace

TEST_CASE("spin reference: four corners per track give the T6 ratio 0.4415, either direction") {
  const std::vector<Eigen::Vector3d> points = corners(0.2);
  const std::vector<double> loads(points.size(), 10.0);
  for (double u : {1.0, -0.5}) {
    const SpinSolution s = coulomb_motion(points, loads, belts(points, u, -u));
    REQUIRE(s.converged);
    const double ratio = s.velocity.z() / (-2 * u / 0.4);
    CHECK(ratio == doctest::Approx(0.4415).epsilon(1e-3));
    CHECK(std::abs(s.velocity.x()) < 1e-9);
    CHECK(residual_of(points, loads, belts(points, u, -u), s.velocity) < 1e-9);
  }
}

TEST_CASE("spin reference: converges with the centre of mass far off the axis, and each direction has its own answer") {
  // A turret far to the front: the loads are very unequal front to back (the case where the
  // damped Newton solve diverged to 1e161).
  const std::vector<Eigen::Vector3d> points = corners(0.2, 0.1);
  const StaticLoads loads = static_loads_on_springs(points, Eigen::Vector3d(0.19, 0.12, 0.3), 200);
  REQUIRE(loads.why.empty());
  const SpinSolution right = coulomb_motion(points, loads.loads, belts(points, 0.5, -0.5));
  const SpinSolution left = coulomb_motion(points, loads.loads, belts(points, -0.5, 0.5));
  REQUIRE(right.converged);
  REQUIRE(left.converged);
  for (const SpinSolution* s : {&right, &left}) {
    CHECK(std::isfinite(s->velocity.z()));
    const double ratio = std::abs(s->velocity.z()) / (2 * 0.5 / 0.4);
    CHECK(ratio > 0);
    CHECK(ratio < 1);
  }
  CHECK(right.velocity.z() < 0);
  CHECK(left.velocity.z() > 0);
  // This vehicle pivots on its most loaded corner; the answer is still the balance, with that
  // corner's friction inside its cone (checked by coulomb_motion) and the other corners sliding.
  CHECK(right.residual < 1e-6);
}

TEST_CASE("spin reference: no belt motion is rest, no loads is said, not answered") {
  const std::vector<Eigen::Vector3d> points = corners(0.2);
  const std::vector<double> loads(points.size(), 10.0);
  const SpinSolution rest = coulomb_motion(points, loads, belts(points, 0, 0));
  CHECK(rest.converged);
  CHECK(rest.velocity.norm() == 0);
  const SpinSolution none = coulomb_motion(points, std::vector<double>(points.size(), 0.0), belts(points, 1, -1));
  CHECK_FALSE(none.converged);
  CHECK(none.why == "no loaded contact points");
}

TEST_CASE("static loads: non-negative, balancing the weight and its moments, refused outside the polygon") {
  const std::vector<Eigen::Vector3d> square = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  StaticLoads l = static_loads_on_springs(square, Eigen::Vector3d(0.5, 0, 0), 100);
  REQUIRE(l.why.empty());
  CHECK(l.loads[1] == doctest::Approx(37.5));  // linear while all four press: 25 + 25·0.5
  // Near the edge the linear plate would pull at the back corners; the springs lift off instead.
  l = static_loads_on_springs(square, Eigen::Vector3d(0.9, 0.3, 0), 100);
  REQUIRE(l.why.empty());
  double sum = 0, mx = 0, my = 0;
  for (std::size_t i = 0; i < square.size(); ++i) {
    CHECK(l.loads[i] >= 0);
    sum += l.loads[i];
    mx += l.loads[i] * square[i].x();
    my += l.loads[i] * square[i].y();
  }
  CHECK(sum == doctest::Approx(100));
  CHECK(mx == doctest::Approx(90));
  CHECK(my == doctest::Approx(30));
  CHECK(l.loads[0] == 0);  // the corner (-1, -1) is lifted
  l = static_loads_on_springs(square, Eigen::Vector3d(1.5, 0.2, 0), 100);
  CHECK(l.loads.empty());
  CHECK(l.why.find("(1.5, 0.2) m, 0.5 m outside the support polygon [(-1, -1), (1, -1), (1, 1), (-1, 1)]") !=
        std::string::npos);
}

TEST_CASE("support polygon: the convex hull, and the margin's sign") {
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {2, 2, 0}, {0, 2, 0}};
  const std::vector<Eigen::Vector2d> hull = support_polygon(points);
  CHECK(hull.size() == 4);  // (1, 1) is inside
  CHECK(polygon_margin(hull, Eigen::Vector2d(1, 1)) == doctest::Approx(1));
  CHECK(polygon_margin(hull, Eigen::Vector2d(1, 0.25)) == doctest::Approx(0.25));
  CHECK(polygon_margin(hull, Eigen::Vector2d(3, 1)) == doctest::Approx(-1));
  CHECK(std::isinf(polygon_margin(support_polygon({{0, 0, 0}, {1, 0, 0}}), Eigen::Vector2d(0.5, 0))));
}
