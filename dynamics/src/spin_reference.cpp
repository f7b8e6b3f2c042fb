// Quasi-static references for skid steering: support polygon, static loads on compression-only
// springs, and the Coulomb steady motion, each a convex problem solved to a tolerance that is
// checked, so that an expected value is never one that did not converge.

#include <bodyfmt/dynamics/spin_reference.h>

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bodyfmt::dynamics {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

}  // namespace

std::vector<Eigen::Vector2d> support_polygon(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector2d> p;
  for (const auto& x : points) p.emplace_back(x.x(), x.y());
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end(),
                      [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return (a - b).norm() < 1e-12; }),
          p.end());
  if (p.size() < 3) return p;
  // Andrew's monotone chain.
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0) --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

double polygon_margin(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  if (polygon.size() < 3) return -std::numeric_limits<double>::infinity();
  double inside = std::numeric_limits<double>::infinity();  // distance to the nearest edge line
  double outside = 0;                                       // distance when beyond an edge
  bool out = false;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const Eigen::Vector2d e = b - a;
    const double side = (e.x() * (p - a).y() - e.y() * (p - a).x()) / e.norm();  // > 0: left, inside
    inside = std::min(inside, side);
    if (side < 0) out = true;
  }
  if (!out) return inside;
  // Outside: the distance to the nearest point of the boundary.
  outside = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    outside = std::min(outside, (a + t * (b - a) - p).norm());
  }
  return -outside;
}

std::string polygon_text(const std::vector<Eigen::Vector2d>& polygon) {
  std::string text;
  for (const auto& c : polygon) text += fmt::format("{}({:.4g}, {:.4g})", text.empty() ? "" : ", ", c.x(), c.y());
  return text;
}

StaticLoads static_loads_on_springs(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& com,
                                    double weight) {
  StaticLoads out;
  const std::vector<Eigen::Vector2d> polygon = support_polygon(points);
  const Eigen::Vector2d c2(com.x(), com.y());
  const double margin = polygon_margin(polygon, c2);
  if (polygon.size() < 3) {
    out.why = fmt::format("the {} floor contact points span no area (support polygon {}): nothing holds the vehicle up",
                          points.size(), polygon_text(polygon));
    return out;
  }
  if (!(margin > 1e-9)) {
    out.why = fmt::format(
        "the centre of mass projects to ({:.4g}, {:.4g}) m, {:.4g} m outside the support polygon [{}] (root frame): no "
        "non-negative contact loads carry it",
        c2.x(), c2.y(), -margin, polygon_text(polygon));
    return out;
  }
  // Φ(c) = Σ ½·max(0, φ_i·c)² − b·c is convex; its minimiser gives Σ N_i·φ_i = b with N_i ≥ 0.
  const Eigen::Vector3d b(weight, weight * com.x(), weight * com.y());
  auto phi = [&](std::size_t i) { return Eigen::Vector3d(1, points[i].x(), points[i].y()); };
  auto value = [&](const Eigen::Vector3d& c) {
    double v = -b.dot(c);
    for (std::size_t i = 0; i < points.size(); ++i) v += 0.5 * std::pow(std::max(0.0, phi(i).dot(c)), 2);
    return v;
  };
  Eigen::Vector3d c(weight / static_cast<double>(points.size()), 0, 0);
  double scale = 0;
  for (const auto& p : points) scale = std::max(scale, std::hypot(p.x(), p.y()));
  const Eigen::Vector3d unit(1, 1 / std::max(scale, 1e-9), 1 / std::max(scale, 1e-9));  // N, N·m → N
  for (int iteration = 0; iteration < 200; ++iteration) {
    Eigen::Vector3d g = -b;
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double s = phi(i).dot(c);
      if (s <= 0) continue;
      g += s * phi(i);
      H += phi(i) * phi(i).transpose();
    }
    if (g.cwiseProduct(unit).norm() <= 1e-10 * weight) {
      for (std::size_t i = 0; i < points.size(); ++i) out.loads.push_back(std::max(0.0, phi(i).dot(c)));
      return out;
    }
    H += 1e-12 * (H.trace() + 1) * Eigen::Matrix3d::Identity();
    const Eigen::Vector3d d = H.ldlt().solve(-g);
    double t = 1;
    const double f0 = value(c);
    while (t > 1e-20 && value(c + t * d) > f0 + 1e-4 * t * g.dot(d)) t /= 2;
    if (t <= 1e-20) break;
    c += t * d;
  }
  out.why = "the static loads did not converge (Newton's method stalled)";
  return out;
}

SpinSolution coulomb_motion(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& loads,
                            const std::vector<Eigen::Vector3d>& belt) {
  SpinSolution out;
  const std::size_t n = points.size();
  double total = 0, radius = 0;
  for (std::size_t i = 0; i < n; ++i) {
    total += loads[i];
    radius = std::max(radius, std::hypot(points[i].x(), points[i].y()));
  }
  if (n == 0 || !(total > 0) || !(radius > 0)) {
    out.why = "no loaded contact points";
    return out;
  }
  auto slip = [&](const Eigen::Vector3d& x, std::size_t i) {
    return Eigen::Vector2d(x[0] - x[2] * points[i].y() + belt[i].x(), x[1] + x[2] * points[i].x() + belt[i].y());
  };
  auto power = [&](const Eigen::Vector3d& x) {
    double f = 0;
    for (std::size_t i = 0; i < n; ++i) f += loads[i] * slip(x, i).norm();
    return f;
  };
  // The friction force and moment on the vehicle are minus the gradient of the power.
  const Eigen::Vector3d unit(1 / total, 1 / total, 1 / (total * radius));
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  double belt_speed = 0;
  for (const auto& v : belt) belt_speed = std::max(belt_speed, v.norm());
  const double stick = 1e-12 * std::max(belt_speed, 1e-9);
  for (int iteration = 0; iteration < 500; ++iteration) {
    out.iterations = iteration;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d W = Eigen::Matrix3d::Zero();  // the reweighted least-squares step's matrix
    Eigen::Vector3d w_rhs = Eigen::Vector3d::Zero();
    bool sticking = false;
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Matrix<double, 2, 3> A;
      A << 1, 0, -points[i].y(), 0, 1, points[i].x();
      const Eigen::Vector2d s = slip(x, i);
      const double norm = s.norm();
      if (loads[i] > 0 && norm < stick) sticking = true;
      const double r = std::max(norm, stick);
      const Eigen::Vector2d u = s / r;
      g += loads[i] * A.transpose() * u;
      H += loads[i] / r * A.transpose() * (Eigen::Matrix2d::Identity() - u * u.transpose()) * A;
      W += loads[i] / r * A.transpose() * A;
      w_rhs += loads[i] / r * A.transpose() * (s - A * x);
    }
    out.residual = g.cwiseProduct(unit).cwiseAbs().maxCoeff();
    if (out.residual <= 1e-10 && !sticking) {
      out.converged = true;
      out.velocity = x;
      return out;
    }
    if (sticking && out.residual <= 1e-10) break;
    // Newton on the convex power, with a reweighted least-squares step (Weiszfeld) when the
    // Hessian gives no descent; either is accepted only with sufficient decrease.
    Eigen::Vector3d d = (H + 1e-14 * (H.trace() + 1) * Eigen::Matrix3d::Identity()).ldlt().solve(-g);
    if (!(g.dot(d) < 0)) d = W.ldlt().solve(-w_rhs) - x;
    const double f0 = power(x);
    double t = 1;
    while (t > 1e-16 && power(x + t * d) > f0 + 1e-4 * t * std::min(g.dot(d), 0.0)) t /= 2;
    if (t <= 1e-16) break;
    x += t * d;
  }
  // At a kink of the power (a point that sticks: a pivot) the minimum is where the sliding
  // points' friction can be balanced by sticking points within their cones: check that.
  out.velocity = x;
  const double still = 1e-6 * std::max(belt_speed, 1e-9);
  Eigen::Vector3d sliding = Eigen::Vector3d::Zero();
  std::vector<std::size_t> stuck;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d sl = slip(x, i);
    if (loads[i] > 0 && sl.norm() < still) {
      stuck.push_back(i);
      continue;
    }
    if (sl.norm() == 0) continue;
    const Eigen::Vector2d u = sl.normalized();
    sliding += loads[i] * Eigen::Vector3d(u.x(), u.y(), points[i].x() * u.y() - points[i].y() * u.x());
  }
  if (stuck.empty()) {
    out.why =
        fmt::format("not converged after {} iterations (residual {:.3g} > 1e-10)", out.iterations + 1, out.residual);
    return out;
  }
  Eigen::MatrixXd A(3, 2 * stuck.size());
  for (std::size_t k = 0; k < stuck.size(); ++k) {
    const Eigen::Vector3d& p = points[stuck[k]];
    A.col(2 * k) = Eigen::Vector3d(1, 0, -p.y());
    A.col(2 * k + 1) = Eigen::Vector3d(0, 1, p.x());
  }
  const Eigen::VectorXd f = A.completeOrthogonalDecomposition().solve(-sliding);
  out.residual = (A * f + sliding).cwiseProduct(unit).cwiseAbs().maxCoeff();
  double worst = 0;  // the most used fraction of a sticking point's friction cone
  for (std::size_t k = 0; k < stuck.size(); ++k)
    worst = std::max(worst, Eigen::Vector2d(f[2 * k], f[2 * k + 1]).norm() / loads[stuck[k]]);
  if (out.residual <= 1e-6 && worst <= 1 + 1e-3) {
    out.converged = true;
    return out;
  }
  out.why = fmt::format(
      "{} loaded contact point(s) stick at the best answer found, but their friction cannot balance the sliding "
      "points' (residual {:.3g}, cone use {:.3g})",
      stuck.size(), out.residual, worst);
  return out;
}

}  // namespace bodyfmt::dynamics
