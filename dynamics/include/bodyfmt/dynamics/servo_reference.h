#pragma once
/// The rigid one-joint references of the tank suite's turret checks (dynamics-checker.md §4
/// T7), computed without a simulation: a joint of constant inertia I about its axis, held by the
/// PD servo τ = P·(q_ref − q) − D·q̇ against the gravity torque τ_g(q) of the links it carries.

#include <functional>
#include <string>
#include <vector>

namespace bodyfmt::dynamics {

struct ServoSag {
  bool converged = false;
  double q = 0;         ///< the sag: τ_g(q) = P·q, the root nearest q = 0
  double residual = 0;  ///< |τ_g(q) − P·q| at the answer (N·m)
  std::string why;      ///< why it did not converge
};

/// Where a servo holding 0 with gain `p_gain` balances `gravity_torque`: Newton's method from
/// q = 0 with steps of at most 0.1 rad. Converged when the residual is within 1e-9 of the
/// torques involved; otherwise says so, with the residual.
ServoSag servo_sag(const std::function<double(double)>& gravity_torque, double p_gain);

/// The joint's position at each of `times` (s, increasing) after the servo's target jumps to
/// `q_ref`, from q0, qd0: I·q̈ = P·(q_ref − q) − D·q̇ + τ_g(q), integrated by RK4 in steps of
/// 0.1 ms.
std::vector<double> servo_step_response(const std::function<double(double)>& gravity_torque, double inertia,
                                        double p_gain, double d_gain, double q0, double qd0, double q_ref,
                                        const std::vector<double>& times);

}  // namespace bodyfmt::dynamics
