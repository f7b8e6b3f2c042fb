#pragma once
/// The dynamics checks: the tank suite (dynamics-checker.md §4) for any model with two
/// pseudo_continuous_track links, and the generic checks for any model. Every expected value is
/// computed from the model (mass, geometry, joint axes and ranges) and from formulas, never from
/// a particular model's names or numbers.

#include <bodyfmt/dynamics/simulation.h>

#include <string>
#include <vector>

namespace bodyfmt::dynamics {

/// One line of a check report: measured against expected within a tolerance.
struct CheckResult {
  std::string name;  ///< e.g. "drive 1 m/s: speed"
  double measured = 0;
  double expected = 0;
  std::string unit;       ///< for printing
  std::string tolerance;  ///< as printed, e.g. "±2 %", "≤ 1e-06 rel"
  bool passed = false;
};

/// What the tank suite found in the model: which tracks are left and right, and the turret.
struct TankLayout {
  LinkIndex left = -1, right = -1;
  /// +1 when +dq on the track drives the vehicle forward (+X of the root), else −1.
  int left_sign = 1, right_sign = 1;
  double spacing = 0;  ///< B: distance between the centres of the two tracks' floor contacts (m)
  /// Floor contact points of each track in the root frame (the lowest vertices).
  std::vector<Eigen::Vector3d> left_points, right_points;
  double lowest_z = 0;   ///< lowest contact point of the model in the root frame
  LinkIndex yaw = -1;    ///< a revolute joint about the vertical, or -1
  LinkIndex pitch = -1;  ///< a revolute joint about a horizontal axis below `yaw`, or -1
};

/// Finds the tank layout, or explains why the model is not a tank in `why`.
std::optional<TankLayout> find_tank(const Model& model, const Derived& derived, const std::vector<ContactPoint>& points,
                                    std::string& why);

/// Quasi-static Coulomb oracle for skid steering (spec §4 T6): the steady yaw rate of a rigid
/// vehicle whose contact points (root frame, z ignored) carry the loads `loads` and whose belts
/// move at `belt` (surface velocity added to each point's velocity, root frame). Returns the
/// yaw rate; independent of μ.
double coulomb_yaw_rate(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& loads,
                        const std::vector<Eigen::Vector3d>& belt);

/// Static loads on coplanar contact points from a rigid body of weight `weight` whose centre
/// of mass projects to `com` (equal-stiffness springs: loads linear in x and y).
std::vector<double> static_loads(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& com, double weight);

struct TankSuiteOptions {
  SimOptions sim;
  double p_gain = 200;  ///< turret servo P (N·m/rad), Choreonoid's TurretController1
  double d_gain = 50;   ///< turret servo D (N·m·s/rad)
};

/// Runs the tank suite. Returns no results and reports why (a located diagnostic, or `why`)
/// when the system cannot be built or the model is not a tank.
/// `layout`, when given, receives what find_tank found.
std::vector<CheckResult> run_tank_suite(const Model& model, const Derived& derived, const TankSuiteOptions& options,
                                        DiagnosticSink& sink, std::string& why, TankLayout* layout = nullptr);

/// The Simbody–MuJoCo cross-check (spec §4 T8): settle, drive, spin and turret scenarios in
/// both engines, MuJoCo 2.2.2 running body2mjcf's export with the belt velocity injected through
/// mjcb_control (spec §3.2). Results: measured = MuJoCo, expected = Simbody. Built only with
/// MuJoCo (BODYFMT_HAVE_MUJOCO_CROSS_CHECK). Not thread-safe (mjcb_control is global).
std::vector<CheckResult> run_mujoco_cross_check(const Model& model, const Derived& derived,
                                                const TankSuiteOptions& options, DiagnosticSink& sink,
                                                std::string& why);

/// The generic checks for any model (spec §4 "Generic checks"): mass matrix symmetric positive
/// definite at random poses, drop onto the floor (no NaN, energy never grows, settles).
std::vector<CheckResult> run_generic_checks(const Model& model, const Derived& derived, const SimOptions& options,
                                            DiagnosticSink& sink, std::string& why);

}  // namespace bodyfmt::dynamics
