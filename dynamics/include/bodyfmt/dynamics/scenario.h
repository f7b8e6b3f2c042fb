#pragma once
/// `bodysim run`: a scenario file (YAML) sets the initial pose, the duration and commands over
/// time; the run writes one CSV row per sample. Format (dynamics/README.md):
///
///   duration: 4            # s
///   sample: 0.01           # s between CSV rows (default 0.01)
///   initial:
///     on_floor: true       # lower the root until the lowest collision point touches z = 0
///     position: [0, 0, 0.1]  # root position (default: the file's); z ignored with on_floor
///     yaw: 0               # rad about world Z (default: the file's orientation)
///     joints: {TURRET_P: 0.2}  # rad or m
///   commands:              # in time order; each holds until a later one changes it
///     - time: 0
///       tracks: {TRACK_L: 1.0, TRACK_R: 1.0}           # belt speeds, m/s
///       joints: {TURRET_P: {target: 0.5, p: 200, d: 50}} # PD servo (rad, N·m/rad, N·m·s/rad)
///     - time: 2
///       joints: {TURRET_Y: {torque: 1.5}}              # a constant torque instead
///
/// Angles are radians. Link names are the model's.

#include <bodyfmt/dynamics/simulation.h>

#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace bodyfmt::dynamics {

struct ScenarioServo {
  std::optional<double> target, p, d, torque;
  SourceLocation p_at, d_at;  ///< where the gains are written
};

struct ScenarioCommand {
  double time = 0;
  std::map<LinkIndex, double> tracks;
  std::map<LinkIndex, ScenarioServo> joints;
  SourceLocation at;
};

struct ScenarioSpec {
  double duration = 1;
  double sample = 0.01;
  SourceLocation at, duration_at, sample_at;  ///< the scenario, its duration and sample values
  bool on_floor = false;
  std::optional<Eigen::Vector3d> position;
  std::optional<double> yaw;
  std::map<LinkIndex, double> joints;
  std::vector<ScenarioCommand> commands;
};

/// Reads a scenario for `model`; reports `dynamics-scenario` (or yaml-*/io-read) located in
/// the scenario file and returns nullopt when it is malformed.
std::optional<ScenarioSpec> read_scenario(const std::string& path, const Model& model, DiagnosticSink& sink);

/// What bodysim simulates at most (bodysim run's --max-* options; README "Limits").
struct ScenarioLimits {
  double max_duration = 600;  ///< simulated seconds
  double max_rows = 1e6;      ///< CSV rows (duration / sample)
  double max_commands = 1e5;  ///< commands in the list
  /// The simulation's step budget (SimOptions::max_steps_per_second; 0: none). Each distinct
  /// command time restarts the integrator, which costs a step at least.
  double max_steps_per_second = 0;
};

/// The values read_scenario() reads but does not judge: the limits above, commands so dense in
/// time that their restarts alone exceed the step budget, and gains that no servo has (a
/// negative P or D pushes away from the target and never settles). Reports each
/// as `dynamics-scenario` at its value; false when any is refused.
bool check_scenario(const ScenarioSpec& scenario, const ScenarioLimits& limits, DiagnosticSink& sink);

/// Runs the scenario and writes the CSV (header, then one row per sample from t = 0): time,
/// root pose (position, quaternion w x y z) and twist (ω, v; world axes), each joint's
/// position and velocity, the total floor contact force and each contacting link's.
/// Returns false (with a diagnostic) when the system cannot be built or the state diverges.
/// `stats`, when given, receives the integration steps taken and the force evaluations.
struct RunStats {
  long long steps = 0;
  long long evaluations = 0;
};
bool run_scenario(const Model& model, const Derived& derived, const ScenarioSpec& scenario, const SimOptions& options,
                  std::ostream& csv, DiagnosticSink& sink, RunStats* stats = nullptr);

}  // namespace bodyfmt::dynamics
