// The turret servo's references (servo_reference.h): the sag by Newton's method, the step
// response by RK4. Both are independent of Simbody: they use the model's derived data through
// the gravity torque the caller gives.

#include <bodyfmt/dynamics/servo_reference.h>

#include <fmt/format.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace bodyfmt::dynamics {

ServoSag servo_sag(const std::function<double(double)>& gravity_torque, double p_gain) {
  ServoSag sag;
  double q = 0;
  for (int i = 0; i < 200; ++i) {
    const double h = 1e-7, f = gravity_torque(q) - p_gain * q;
    const double df = (gravity_torque(q + h) - gravity_torque(q - h)) / (2 * h) - p_gain;
    if (df == 0) break;
    q -= std::clamp(f / df, -0.1, 0.1);
  }
  const double tau = gravity_torque(q);
  sag.q = q;
  sag.residual = std::abs(tau - p_gain * q);
  const double scale = std::max({std::abs(tau), p_gain * std::abs(q), std::abs(gravity_torque(0))});
  sag.converged = std::isfinite(q) && sag.residual <= 1e-9 * scale + 1e-12;
  if (!sag.converged)
    sag.why = fmt::format(
        "Newton's method on τ_g(q) = P·q (P = {:g} N·m/rad) stopped at q = {:.6g} rad with τ_g − P·q = {:.3g} N·m",
        p_gain, q, tau - p_gain * q);
  return sag;
}

std::vector<double> servo_step_response(const std::function<double(double)>& gravity_torque, double inertia,
                                        double p_gain, double d_gain, double q0, double qd0, double q_ref,
                                        const std::vector<double>& times) {
  auto rhs = [&](const Eigen::Vector2d& x) {
    return Eigen::Vector2d(x[1], (p_gain * (q_ref - x[0]) - d_gain * x[1] + gravity_torque(x[0])) / inertia);
  };
  const double h = 1e-4;
  Eigen::Vector2d x(q0, qd0);
  std::vector<double> out;
  long step = 0;
  for (const double t : times) {
    for (const long n = std::lround(t / h); step < n; ++step) {
      const Eigen::Vector2d k1 = rhs(x), k2 = rhs(x + h / 2 * k1), k3 = rhs(x + h / 2 * k2), k4 = rhs(x + h * k3);
      x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    out.push_back(x[0]);
  }
  return out;
}

}  // namespace bodyfmt::dynamics
