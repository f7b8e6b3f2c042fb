#pragma once
/// The quasi-static references of the tank suite, computed from contact points and the centre
/// of mass alone (no simulation): the support polygon, the static loads of a rigid vehicle on
/// compression-only springs, and the steady skid-steering motion under Coulomb friction
/// (dynamics-checker.md §4 T6). Both solves are convex minimisations: they converge or say why.

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::dynamics {

/// The convex hull of points projected onto the floor (x, y), counter-clockwise.
std::vector<Eigen::Vector2d> support_polygon(const std::vector<Eigen::Vector3d>& points);

/// Signed distance of `p` from the boundary of the convex polygon: positive inside, negative
/// outside; -infinity for a polygon of fewer than three corners (no area).
double polygon_margin(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

/// "(x, y), (x, y), ..." in metres, for messages.
std::string polygon_text(const std::vector<Eigen::Vector2d>& polygon);

struct StaticLoads {
  std::vector<double> loads;  ///< per point, ≥ 0, summing to the weight
  std::string why;            ///< empty when solved; else why there are no loads
};

/// Static loads N_i = max(0, c0 + c1·x_i + c2·y_i) of a rigid body of weight `weight`, whose
/// centre of mass projects to `com`, on coplanar points carried by equal compression-only
/// springs: the minimiser of a convex function, found by Newton's method with a line search.
/// Refused (why) when the centre of mass is not strictly inside the support polygon.
StaticLoads static_loads_on_springs(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& com,
                                    double weight);

struct SpinSolution {
  bool converged = false;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< (v_x, v_y, ω) of the root frame
  double residual = 0;  ///< the largest of |ΣF|/ΣN and |ΣM|/(ΣN·r_max) at the answer
  int iterations = 0;
  std::string why;  ///< empty when converged
};

/// Steady quasi-static motion of a rigid vehicle whose points (root frame, z ignored) carry
/// `loads` and whose belts add `belt` to each point's slip: the minimiser of the friction
/// power Σ N_i·|slip_i|, which is convex in (v_x, v_y, ω); at the minimum the net friction
/// force and moment vanish. Independent of μ. Not converged (why) when a point sticks at the
/// minimum (the balance is then not that of sliding friction) or the tolerance is not reached.
SpinSolution coulomb_motion(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& loads,
                            const std::vector<Eigen::Vector3d>& belt);

}  // namespace bodyfmt::dynamics
