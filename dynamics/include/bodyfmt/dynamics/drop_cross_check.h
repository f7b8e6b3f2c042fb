#pragma once
/// `bodysim check --cross-check mujoco`: the locked-joint drop of the generic checks (a model
/// with a free root, every joint welded at its initial position, released 2 cm above the floor)
/// runs in Simbody and in MuJoCo 2.2.2 on body2mjcf's export of the same model, and the two
/// engines' rest height, rest orientation, floor force ΣN and settle time are compared within
/// the tolerances of dynamics-checker.md §4 T8 (dynamics/README.md, "Drop cross-check").
/// Built only with MuJoCo (BODYFMT_HAVE_MUJOCO_CROSS_CHECK). Not thread-safe.

#include <bodyfmt/dynamics/checks.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace bodyfmt::dynamics {

/// One engine's drop, measured the same way in both.
struct DropMeasures {
  double height = 0;  ///< root origin z at the end (m)
  /// Root orientation at the end.
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double turned = 0;              ///< angle of the root's rotation since release (rad)
  double floor_force = 0;         ///< ΣN, mean over the last 0.5 s (N)
  double settle_time = 0;         ///< from release to the last sample outside the rest band (s)
  double first_contact = 0;       ///< from release to the first floor force (s)
  double orientation_settle = 0;  ///< from release to the last sample outside the orientation band (s)
  double kinetic_energy = 0;      ///< at the end (J)
  double penetration = 0;         ///< deepest point below the floor at the end (m)
  int contacts = 0;               ///< points (Simbody) or contacts (MuJoCo) under the floor at the end
  /// Fewest and most contacts over the last 0.5 s: a rest that switches between contact sets.
  int contacts_min = 0, contacts_max = 0;
  /// How fast the root still turns at the end: the angle between its orientations 0.1 s
  /// before the end and at the end, over 0.1 s (rad/s). A rest that creeps shows here; the
  /// last of a settling has died out by then.
  double turn_rate = 0;
  /// The impact, which sets the settle time: how far the root sank below its rest height, and
  /// how far it rose above it afterwards (a bounce), in m.
  double impact_sink = 0;
  double rebound = 0;
  /// The support it comes to rest on (measured on Simbody's contact points): the points that
  /// touch the floor at the end, the largest horizontal distance between them (m), and when
  /// the last of them first came down onto the floor (s) and how fast (m/s): the support's
  /// last impact.
  int support_points = 0;
  double support_span = 0;
  /// Its narrowest horizontal width (m): a tilt of the rest by 0.5 mm across it is within the
  /// height band (the span when the support is a point or a line).
  double support_width = 0;
  /// When the support is a line (two points, or all on one line: a roller on its side), its
  /// direction in the root's axes; zero otherwise. Resting on a line, how far the model turned
  /// about it is decided by the impacts, as its yaw is.
  Eigen::Vector3d support_line = Eigen::Vector3d::Zero();
  double support_time = 0;
  double support_speed = 0;
  /// Landed tilted from its rest (more than 1e-3 rad at first contact) and tipped onto its
  /// support afterwards: that second impact, not the first, sets the end of the settle.
  bool tipped = false;
};

struct DropCrossCheckOptions {
  SimOptions sim;  ///< Simbody's options; μ also goes on every MuJoCo geom
  /// Applied to the (already welded) export before MuJoCo compiles it; for tests that show the
  /// cross-check catches a defective export. Empty: the export as written.
  std::function<bool(const std::filesystem::path& mjcf, std::string& why)> mutate_export;
};

/// What the cross-check measured, for reports.
struct DropCrossCheckReport {
  DropMeasures simbody, mujoco;
  double drop_height = 0;  ///< release height of the lowest contact point (m)
  /// MuJoCo's soft contact alone: the time its linear spring-damper (solref, solimp) needs to
  /// bring the impact that sets the settle back within the rest band (s), and its time
  /// constant (solref[0], s). The impact is the first contact at the free-fall speed, into the
  /// height band; for a model that tipped, Simbody's tip onto its support at the support's
  /// descent speed, into the tighter of the height band and the orientation band across the
  /// support (1e-3 rad × support_span).
  double mujoco_relaxation = 0;
  double mujoco_time_constant = 0;
  double relaxation_speed = 0;  ///< m/s
  double relaxation_band = 0;   ///< m
  /// When the impact that sets the settle happened in Simbody (s): its first contact, or, when
  /// it tipped, the first touch of the last point of its rest support.
  double impact_time = 0;
  /// What MuJoCo's settle time is compared with: impact_time plus MuJoCo's relaxation, or
  /// Simbody's orientation settle when that is later (s).
  double expected_settle = 0;
  /// MuJoCo 2.2.2 collides a mesh with a plane at its deepest vertex plus at most 2 of that
  /// vertex's convex-hull neighbours, skipping a neighbour closer to it than 0.3·rbound (the
  /// geom's bounding-sphere radius): that distance (m), the smallest and largest over the
  /// export's collision meshes; 0 when it has none.
  double mesh_contact_skip_min = 0, mesh_contact_skip_max = 0;
  int collision_meshes = 0;
};

/// Runs the drop in both engines and compares them (measured = MuJoCo, expected = Simbody).
/// Returns no results and says why when the model has no free root, nothing to drop, or an
/// engine cannot load it.
std::vector<CheckResult> run_drop_cross_check(const Model& model, const Derived& derived,
                                              const DropCrossCheckOptions& options, DiagnosticSink& sink,
                                              std::string& why, DropCrossCheckReport* report = nullptr);

/// The measurements of both engines, two indented lines for bodysim's header.
std::string describe(const DropCrossCheckReport& report);

}  // namespace bodyfmt::dynamics
