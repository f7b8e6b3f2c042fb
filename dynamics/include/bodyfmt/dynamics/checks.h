#pragma once
/// The dynamics checks: the tank suite (dynamics-checker.md §4) for any model with two
/// pseudo_continuous_track links, and the generic checks for any model. Every expected value is
/// computed from the model (mass, geometry, joint axes and ranges) and from formulas, never from
/// a particular model's names or numbers.

#include <bodyfmt/dynamics/simulation.h>
#include <bodyfmt/dynamics/spin_reference.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::dynamics {

/// One line of a check report: measured against expected within a tolerance.
struct CheckResult {
  CheckResult() = default;
  CheckResult(std::string name_, double measured_, double expected_, std::string unit_, std::string tolerance_,
              bool passed_)
      : name(std::move(name_)),
        measured(measured_),
        expected(expected_),
        unit(std::move(unit_)),
        tolerance(std::move(tolerance_)),
        passed(passed_) {}
  std::string name;  ///< e.g. "drive 1 m/s: speed"
  double measured = 0;
  double expected = 0;
  std::string unit;       ///< for printing
  std::string tolerance;  ///< as printed, e.g. "±2 %", "≤ 1e-06 rel"
  bool passed = false;
  /// Not run: printed as `SKIP  name: note` and counted apart from passes and failures.
  bool skipped = false;
  /// A cause in words, printed instead of the numbers (`FAIL  name: note`), or why skipped.
  std::string note;
  /// Compares the Simbody system with the derived data it was built from: a self-test of the
  /// build, not of the model (listed apart).
  bool self_test = false;
};

/// A check that cannot apply, with the reason.
CheckResult skipped_check(std::string name, std::string reason);
/// A check decided without numbers, with its cause or finding in words.
CheckResult verdict_check(std::string name, bool passed, std::string note);

/// What the tank suite found in the model: which tracks are left and right, and the turret.
struct TankLayout {
  LinkIndex left = -1, right = -1;
  /// +1 when +dq on the track drives the vehicle forward (+X of the root), else −1.
  int left_sign = 1, right_sign = 1;
  /// The tracks' joint axes in the root frame at the file pose.
  Eigen::Vector3d left_axis = Eigen::Vector3d::Zero(), right_axis = Eigen::Vector3d::Zero();
  /// Why the vehicle does not stand on its two tracks (a track above the floor, another link
  /// lower than the tracks), or empty.
  std::string standing_problem;
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

/// The cause both the suite and its cross-check name when the tracks disagree: "tracks drive
/// against each other: "L" (axis (x, y, z) in the root frame) drives toward +X and "R" (axis
/// ...) toward -X for +dq".
std::string tracks_against_each_other(const Model& model, const TankLayout& tank);

/// What the tank suite and its MuJoCo cross-check both start from, found once from the model:
/// the system built as the options build it, the tank layout, the pose it starts in, the
/// joints a controller holds, where the same +dq on both tracks drives it, and the turret's
/// pitch step.
struct TankOpening {
  /// The first build of the system (it reports the model's findings, e.g. a balanced inertia).
  std::unique_ptr<Simulation> probe;
  std::vector<ContactPoint> contacts;  ///< the system's floor contact points
  TankLayout tank;
  /// The root pose the scenarios start from: the file pose lowered until the lowest contact
  /// point touches the floor.
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  /// Every revolute and prismatic joint: held at 0 by servos, as a controller holds them.
  std::vector<LinkIndex> held_joints;
  /// +1 or −1: the root's x direction in which the same +dq on both tracks drives the vehicle;
  /// 0 when the tracks drive against each other.
  int drive_direction = 0;
  /// The turret pitch step target: two thirds of the wider side of the range (at most 30°), or
  /// of the other side when that would put the turret into the floor; 0 when there is none,
  /// with the reason in `no_pitch_step` (empty without a pitch joint).
  double pitch_step = 0;
  std::string no_pitch_step;
};

/// Builds the system and finds the tank (find_tank). Returns nullopt with `why` (or a located
/// diagnostic in `sink`) when the system cannot be built or the model is not a tank.
std::optional<TankOpening> open_tank(const Model& model, const Derived& derived, const SimOptions& options,
                                     DiagnosticSink& sink, std::string& why);

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

/// The Simbody–MuJoCo cross-check (spec §4 T8): from the suite's opening (open_tank), settle,
/// drive, spin and turret scenarios in both engines with the same commands (the same dq to both
/// tracks to drive), MuJoCo 2.2.2 running body2mjcf's export with the belt velocity injected
/// through mjcb_control (spec §3.2). Each engine's drive must go straight; the "MuJoCo vs
/// Simbody" results have measured = MuJoCo, expected = Simbody. Built only with
/// MuJoCo (BODYFMT_HAVE_MUJOCO_CROSS_CHECK). Not thread-safe (mjcb_control is global).
std::vector<CheckResult> run_mujoco_cross_check(const Model& model, const Derived& derived,
                                                const TankSuiteOptions& options, DiagnosticSink& sink,
                                                std::string& why);

/// The generic checks' joint stops are no stiffer than I·ω² with this ω (rad/s; I the inertia of
/// the joint's subtree about its axis, its mass for a slider): SimOptions::stop_frequency_limit.
constexpr double kGenericStopFrequency = 300;
/// ... and no softer than I·ω² with this ω: SimOptions::stop_frequency_floor. A fixed 10⁴ per rad
/// (or m) gives way under a heavy subtree's own servo (a 713 kg plate's joint went 1.5° past).
constexpr double kGenericStopFloorFrequency = 30;

/// The generic checks for any model (spec §4 "Generic checks"): mass matrix symmetric positive
/// definite at random poses, drop onto the floor (no NaN, energy never grows, settles).
std::vector<CheckResult> run_generic_checks(const Model& model, const Derived& derived, const SimOptions& options,
                                            DiagnosticSink& sink, std::string& why);

}  // namespace bodyfmt::dynamics
