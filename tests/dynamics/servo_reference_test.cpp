// The turret servo's references (servo_reference.h) against closed forms worked out here: the
// sag of a constant and of a linear gravity torque, a pendulum's sag against bisection, a servo
// with no equilibrium said, and the step response of the linear second-order system, overdamped
// and underdamped.
#include <doctest/doctest.h>

#include <bodyfmt/dynamics/servo_reference.h>

#include <cmath>
#include <complex>

using namespace bodyfmt::dynamics;

namespace {

/// q(t) of I·q̈ + D·q̇ + P·q = P·q_ref + τ0 from q0, qd0: the homogeneous solution about the
/// equilibrium q∞ = q_ref + τ0/P, with complex roots for the underdamped case.
double linear_step(double I, double P, double D, double tau0, double q0, double qd0, double q_ref, double t) {
  const double q_inf = q_ref + tau0 / P;
  const std::complex<double> disc = std::sqrt(std::complex<double>(D * D - 4 * P * I));
  const std::complex<double> r1 = (-D + disc) / (2 * I), r2 = (-D - disc) / (2 * I);
  // A + B = q0 − q∞, r1·A + r2·B = qd0.
  const std::complex<double> B = (qd0 - r1 * (q0 - q_inf)) / (r2 - r1);
  const std::complex<double> A = (q0 - q_inf) - B;
  return q_inf + (A * std::exp(r1 * t) + B * std::exp(r2 * t)).real();
}

}  // namespace

TEST_CASE("servo reference: the sag of a constant torque is τ0/P, of a linear one τ0/(P + k)") {
  const ServoSag constant = servo_sag([](double) { return -6.1; }, 200);
  CHECK(constant.converged);
  CHECK(constant.q == doctest::Approx(-6.1 / 200).epsilon(1e-12));
  const ServoSag linear = servo_sag([](double q) { return 3.0 - 40 * q; }, 200);
  CHECK(linear.converged);
  CHECK(linear.q == doctest::Approx(3.0 / 240).epsilon(1e-12));
  CHECK(linear.residual < 1e-12);
}

TEST_CASE("servo reference: a pendulum's sag is the root of m·g·l·cos q = P·q nearest 0") {
  // A 2.5 kg cannon 0.25 m from its pitch axis, horizontal at q = 0 (ScoutTank's proportions),
  // on a servo of 10 N·m/rad: a sag of about half a radian, where the nonlinearity matters.
  const double mgl = 2.5 * 9.80665 * 0.25, P = 10;
  auto tau = [&](double q) { return -mgl * std::cos(q); };
  const ServoSag sag = servo_sag(tau, P);
  REQUIRE(sag.converged);
  // Bisection on f(q) = −mgl·cos q − P·q, which falls from f(−π/2) = P·π/2 > 0 to f(0) < 0.
  double lo = -M_PI / 2, hi = 0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (tau(mid) - P * mid > 0 ? lo : hi) = mid;
  }
  CHECK(sag.q == doctest::Approx(0.5 * (lo + hi)).epsilon(1e-9));
  CHECK(sag.q < -0.4);
}

TEST_CASE("servo reference: a servo that cannot balance the torque is said, not answered") {
  const ServoSag none = servo_sag([](double) { return 10.0; }, 0);  // no spring: no equilibrium
  CHECK(!none.converged);
  CHECK(none.why.find("τ_g − P·q = 10 N·m") != std::string::npos);
  // A torque that jumps across zero has no root either; Newton's method ends beside the jump.
  const ServoSag jump = servo_sag([](double q) { return q < 0.05 ? 20.0 : -20.0; }, 1);
  CHECK(!jump.converged);
  CHECK(jump.residual > 1);
}

TEST_CASE("servo reference: the step response is the linear system's closed form, over- and underdamped") {
  const std::vector<double> times = {0.25, 0.5, 1.0, 2.0};
  struct Case {
    double I, P, D, tau0, q0, qd0, q_ref;
  };
  // The turret servo (P = 200, D = 50) on 0.15 kg·m² (ζ ≈ 4.6), and a lightly damped one (ζ ≈ 0.03).
  for (const Case c : {Case{0.15, 200, 50, -1.96, -0.0098, 0.0, 0.5236}, Case{0.15, 200, 0.3, 0.0, 0.1, -0.5, -0.3}}) {
    CAPTURE(c.D);
    const std::vector<double> q =
        servo_step_response([&](double) { return c.tau0; }, c.I, c.P, c.D, c.q0, c.qd0, c.q_ref, times);
    REQUIRE(q.size() == times.size());
    for (std::size_t k = 0; k < times.size(); ++k) {
      const double t = times[k];
      CAPTURE(t);
      CHECK(q[k] == doctest::Approx(linear_step(c.I, c.P, c.D, c.tau0, c.q0, c.qd0, c.q_ref, t)).epsilon(1e-9));
    }
  }
  // A restoring gravity torque −k·q is a stiffer spring: the closed form with P + k.
  const double k = 30;
  const std::vector<double> q =
      servo_step_response([&](double x) { return -k * x; }, 0.15, 200, 50, 0.0, 0.0, 0.4, {1.0, 2.0});
  CHECK(q[1] ==
        doctest::Approx(linear_step(0.15, 200 + k, 50, 0.0, 0.0, 0.0, 0.4 * 200 / (200 + k), 2.0)).epsilon(1e-9));
}
