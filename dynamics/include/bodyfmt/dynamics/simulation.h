#pragma once
/// A Simbody multibody system built from a loaded Model: one mobilized body per link (Free,
/// Pin, Slider, Weld), mass properties from compute_derived, point contacts of every collision
/// shape's tessellated vertices against the floor z = 0 with regularized Coulomb friction, belt
/// surface velocity for pseudo_continuous_track links (dynamics-checker.md §1.4), joint-range
/// stops and PD joint servos. Simbody stays behind this interface: nothing else in the project
/// includes its headers.

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <Eigen/Geometry>

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace bodyfmt::dynamics {

/// Ground contact: a compliant floor z = 0 touched by contact points (README of dynamics/).
struct ContactParams {
  double friction = 0.5;  ///< Coulomb μ (Choreonoid's default material pair, spec §1.1)
  /// Normal stiffness per contact point (N/m). 0: chosen from the model so that its weight on
  /// four points sinks `reference_depth`: k = m·g / (4·reference_depth).
  double stiffness = 0;
  double reference_depth = 1e-4;      ///< m
  double dissipation = 5;             ///< Hunt–Crossley c (s/m): f = k·δ·(1 + c·δ̇), never pulling
  double transition_velocity = 0.05;  ///< m/s: friction grows as μ·x·(2 − x), x = |slip|/vt < 1
};

/// Which floor contact model carries the model (dynamics/README.md "Floor contact").
enum class ContactModel {
  kPoints,   ///< Force::Custom point contact at the collision shapes' vertices (the default)
  kSimbody,  ///< Simbody's CompliantContactSubsystem: HalfSpace floor, Bricks, elastic-foundation meshes
};

struct SimOptions {
  double gravity = 9.80665;  ///< along −Z of the world, or along gravity_direction
  /// The direction of gravity in the world (a tilted floor, for the tip-slope check).
  Eigen::Vector3d gravity_direction = -Eigen::Vector3d::UnitZ();
  bool contact = true;
  ContactModel contact_model = ContactModel::kPoints;
  bool joint_stops = true;      ///< enforce joint_range (our choice; AIST does not, spec §0.7)
  double stop_stiffness = 1e4;  ///< N·m/rad or N/m
  double stop_dissipation = 1;  ///< Simbody MobilityLinearStop's c
  /// > 0: no stop stiffer than I·ω² (rad/s; I the inertia of the joint's subtree about its axis,
  /// or its mass for a slider), so that no stop rings faster than ω; 0: stop_stiffness for all.
  double stop_frequency_limit = 0;
  /// > 0: no stop softer than I·ω² (rad/s, the same I), so that a heavy subtree does not push
  /// through its stop; 0: no floor. Applied after stop_frequency_limit.
  double stop_frequency_floor = 0;
  double accuracy = 1e-5;        ///< RungeKuttaMersonIntegrator accuracy
  bool balance_inertia = false;  ///< use bodyfmt::balance_inertia for invalid tensors
  bool lock_joints = false;      ///< weld every joint at its initial position (a rigid body)
  ContactParams contact_params;
  /// The work budget of every simulation (0: unbounded): integrator steps per simulated second
  /// (a stiff contact or servo makes the explicit integrator crawl), and the process's CPU seconds.
  double max_steps_per_second = 5e4;
  double max_cpu_seconds = 300;
};

/// Thrown by Simulation::advance_to() when the work budget is spent: the message says which
/// limit and the likely cause; `where` is the link (or shape) responsible, or the model.
class WorkBudgetExceeded : public std::runtime_error {
 public:
  WorkBudgetExceeded(const std::string& message, SourceLocation at, bool commands = false)
      : std::runtime_error(message), where(at), by_commands(commands) {}
  SourceLocation where;
  bool by_commands;  ///< restarts for new commands were most of the steps: the caller knows where they are
};

/// Thrown by Simulation::advance_to() when Simbody itself throws: the engine's message with the
/// likely cause in the model, and `where` at it.
class EngineFailure : public std::runtime_error {
 public:
  EngineFailure(const std::string& message, SourceLocation at) : std::runtime_error(message), where(at) {}
  SourceLocation where;
};

/// A joint servo: τ = P·(q_ref(t) − q) + D·(q̇_ref(t) − q̇) + feed-forward torque.
struct JointServo {
  double p_gain = 0;
  double d_gain = 0;
  std::function<double(double)> q_ref;   ///< of time; null: 0
  std::function<double(double)> qd_ref;  ///< of time; null: 0
  double torque = 0;
};

/// Points on each circle of a cylinder (a symmetric set about the lowest point, so that the
/// normal forces on it are conservative as the lowest point moves round the rim).
constexpr int kRimPoints = 20;

/// A point of a link that touches the floor: a vertex (radius 0), the centre of a sphere (a
/// Sphere shape, a Capsule's end) whose lowest point touches it, or one of kRimPoints points
/// spread evenly round a circle (a Cylinder's end: rim_axis is not zero), counted from the
/// circle's lowest point as the link turns. A cylinder on its side then touches along its
/// lowest line, as a real one does, and one standing on an end rests on its whole rim.
struct ContactPoint {
  LinkIndex link = -1;
  Eigen::Vector3d position_in_link = Eigen::Vector3d::Zero();  ///< the vertex, or the sphere's or circle's centre
  double radius = 0;
  Eigen::Vector3d rim_axis = Eigen::Vector3d::Zero();  ///< the circle's normal, link frame, unit; zero: no circle
  /// In the circle's plane, link frame, unit: where the points start when the circle lies flat
  /// and has no lowest point.
  Eigen::Vector3d rim_start = Eigen::Vector3d::Zero();
  double rim_angle = 0;             ///< round the rim from its lowest point, rad
  double rim_cos = 1, rim_sin = 0;  ///< of rim_angle, computed once: the force evaluation needs them

  bool is_sphere() const { return radius > 0 && rim_axis.isZero(); }
  /// Where the point touches a floor below, from the link origin in world axes, for the link
  /// turned by R: the vertex, the sphere's lowest point, or the point's place on the rim.
  Eigen::Vector3d offset(const Eigen::Matrix3d& R) const;
  /// The same point in the world, for the link at X_WL.
  Eigen::Vector3d touching(const Eigen::Isometry3d& X_WL) const { return X_WL.translation() + offset(X_WL.linear()); }
  /// The highest point of the same shape part (the sphere's top; the rim point itself, the
  /// rim's top being one of its points), for vertical extents.
  Eigen::Vector3d top(const Eigen::Isometry3d& X_WL) const {
    return is_sphere() ? X_WL * position_in_link + Eigen::Vector3d(0, 0, radius) : touching(X_WL);
  }
};

class Simulation {
 public:
  /// Builds the system. Reports invalid inertias with the bodycheck rule ids
  /// (inertia-triangle, inertia-not-positive-definite) and returns nullptr unless
  /// options.balance_inertia, in which case the balanced tensor is used and reported
  /// (dynamics-inertia-balanced). Also nullptr (with a diagnostic) for what Simbody cannot
  /// build: a negative or non-finite mass, a massless moving link.
  static std::unique_ptr<Simulation> build(const Model& model, const Derived& derived, const SimOptions& options,
                                           DiagnosticSink& sink);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const Model& model() const;
  /// Where each link touches the floor, in the link frame: collision-shape vertices (points
  /// model), or Brick corners and elastic-foundation springs (face centroids; simbody model).
  const std::vector<ContactPoint>& contact_points() const;
  /// The stiffness per contact point (or Brick vertex) actually used (N/m).
  double contact_stiffness() const;
  /// simbody model: the elastic-foundation stiffness (N/m³), the numbers of Bricks, meshes and
  /// mesh faces; zeros otherwise.
  double mesh_stiffness() const;
  int contact_bricks() const;
  int contact_meshes() const;
  int contact_mesh_faces() const;
  /// The inertia about the centre of mass used for each link (after balancing).
  const std::vector<Eigen::Matrix3d>& link_inertias() const;

  // --- Initial state (before start(), or followed by restart()) ---------------------------
  /// Root pose in the world (free roots only; a fixed root stays at its file pose).
  void set_root_pose(const Eigen::Isometry3d& X_WR);
  /// Root twist: angular and linear velocity of the root origin, both in world axes.
  void set_root_velocity(const Eigen::Vector3d& omega, const Eigen::Vector3d& v);
  void set_joint_position(LinkIndex link, double q);
  void set_joint_velocity(LinkIndex link, double qd);
  void set_time(double t);

  // --- Commands (take effect at the current time; the integrator restarts) ---------------
  void set_track_speed(LinkIndex link, double dq);
  void set_servo(LinkIndex link, JointServo servo);
  void clear_servo(LinkIndex link);

  /// Starts or restarts integration from the current state (after commands changed).
  void restart();
  /// Throws WorkBudgetExceeded when the budget of SimOptions is spent (advance_to() and the
  /// force elements call it).
  void check_budget() const;
  /// Integrates to time t (restart() first when commands changed since the last step).
  void advance_to(double t);

  // --- Queries on the current state ------------------------------------------------------
  double time() const;
  Eigen::Isometry3d link_pose(LinkIndex link) const;
  /// Spatial velocity of the link frame: angular and linear (origin), both in world axes.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> link_velocity(LinkIndex link) const;
  double joint_position(LinkIndex link) const;
  double joint_velocity(LinkIndex link) const;
  bool has_joint(LinkIndex link) const;  ///< revolute or prismatic
  double total_mass() const;
  Eigen::Vector3d center_of_mass() const;
  Eigen::Vector3d center_of_mass_velocity() const;
  /// Angular momentum about the centre of mass and linear momentum, world axes.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> central_momentum() const;
  double kinetic_energy() const;
  /// Kinetic plus potential (gravity about z = 0, contact and stop springs).
  double energy() const;
  /// Sum of the floor contact forces on `link`, or on the whole model (-1), world axes.
  Eigen::Vector3d total_contact_force(LinkIndex link = -1) const;
  /// Deepest penetration of any contact point of `link` (or of all links: -1) into the floor
  /// (m; negative when above it).
  double max_penetration(LinkIndex link = -1) const;
  /// The joint-space mass matrix at the current positions (generalized speeds: the root's six,
  /// angular first, then one per joint in link order).
  Eigen::MatrixXd mass_matrix() const;
  /// Index of a link's joint speed in mass_matrix(), or -1.
  int mobility_index(LinkIndex link) const;
  /// Number of integration steps taken since build.
  long long steps_taken() const;
  /// Number of force evaluations (the integrator's derivative calls, rejected steps included).
  long long force_evaluations() const;
  /// True when every coordinate and speed is finite.
  bool finite() const;
  /// Sets every joint to q and the root to X and returns the mass matrix there.
  Eigen::MatrixXd mass_matrix_at(const std::vector<double>& q_by_link);

  struct Impl;  ///< the Simbody system (simulation.cpp); public only for its force elements

 private:
  Simulation();
  /// The likely cause of slow integration, in words; `where` is set to its source.
  std::string stiffest_part(SourceLocation& where) const;
  /// Internal integrator steps between looks at the budget.
  static constexpr int kBudgetChunk = 500;
  std::unique_ptr<Impl> impl_;
};

/// Inertia of the subtree rooted at `link` about the joint axis of `link`, at joint positions
/// `q` (by link), computed from the model's derived data alone (an independent reference for
/// the simulated mass matrix). `inertias` overrides the per-link inertia when not empty.
double subtree_axis_inertia(const Model& model, const Derived& derived, LinkIndex link, const std::vector<double>& q,
                            const std::vector<Eigen::Matrix3d>& inertias = {});

/// Gravity torque (or force, for a prismatic joint) on joint `link` along +q, from the
/// subtree's weight at joint positions `q`, with the root at its file pose.
double subtree_gravity_torque(const Model& model, const Derived& derived, LinkIndex link, const std::vector<double>& q,
                              double gravity);

}  // namespace bodyfmt::dynamics
