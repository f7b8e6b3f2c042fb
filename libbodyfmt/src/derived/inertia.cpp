#include <bodyfmt/inertia.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

namespace bodyfmt {

// Halving before adding keeps a tensor of finite entries finite (1e308 + 1e308 overflows).
Eigen::Matrix3d symmetrized_inertia(const Eigen::Matrix3d& inertia) {
  return 0.5 * inertia + 0.5 * inertia.transpose();
}

PrincipalInertia principal_inertia(const Eigen::Matrix3d& inertia) {
  const Eigen::Matrix3d sym = symmetrized_inertia(inertia);
  PrincipalInertia p;
  if (sym(0, 1) == 0 && sym(0, 2) == 0 && sym(1, 2) == 0) {
    std::array<int, 3> order = {0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return sym(a, a) < sym(b, b); });
    p.axes.setZero();
    for (int i = 0; i < 3; ++i) {
      p.moments[i] = sym(order[i], order[i]);
      p.axes(order[i], i) = 1;
    }
    p.exact = true;
    return p;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(sym);
  p.moments = solver.eigenvalues();
  p.axes = solver.eigenvectors();
  return p;
}

InertiaValidity inertia_validity(const PrincipalInertia& p) {
  InertiaValidity v;
  const double trace = p.moments.sum();
  // Drake's tolerance for a negative moment, ε = 16·DBL_EPSILON·max(1, tr/2).
  const double drake_eps = 16 * DBL_EPSILON * std::max(1.0, std::abs(trace) / 2);
  v.negative_moment = p.moments[0] < -(p.exact ? 0.0 : drake_eps);
  v.triangle_margin = p.moments[0] + p.moments[1] - p.moments[2];
  const double rounding = p.exact ? 0.0 : 4 * DBL_EPSILON * std::abs(trace);
  v.triangle = !v.negative_moment && v.triangle_margin < -rounding;
  return v;
}

std::optional<Eigen::Matrix3d> balance_inertia(const Eigen::Matrix3d& inertia) {
  const PrincipalInertia p = principal_inertia(inertia);
  if (inertia_validity(p).valid()) return std::nullopt;
  Eigen::Vector3d m = p.moments.cwiseMax(0.0);
  std::sort(m.data(), m.data() + 3);  // clamping keeps the order; sorting states it
  // Every balanced tensor keeps a margin s: MuJoCo re-derives the moments from what is written
  // and checks A + B >= C without tolerance, and rounding must not undo the balance.
  const double s = 1e-7 * m.sum();
  const double excess = m[2] - m[0] - m[1];
  if (excess + s > 0) {
    const double t = (excess + s) / 3;
    m += Eigen::Vector3d(t, t, -t);
    // Moving the two largest towards each other can pass them (they were nearly equal, e.g.
    // moments (-1, 1, 1)): then both inequalities that hold them are active, the nearest valid
    // pair is their mean, and the smallest needs the whole margin.
    if (m[1] > m[2]) {
      m[1] = m[2] = (m[1] + m[2]) / 2;
      m[0] = std::max(m[0], s);
    }
  }
  if (m.isZero(0)) return std::nullopt;
  return Eigen::Matrix3d(p.axes * m.asDiagonal() * p.axes.transpose());
}

}  // namespace bodyfmt
