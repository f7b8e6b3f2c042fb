#pragma once
/// The physical-validity gate: whether each link's mass and inertia are physical and whether
/// each joint is usable, decided once for bodycheck's inertia and joint rules, the exporters'
/// preflight, body2mjcf and bodysim's Simbody builder. Each tool words a finding in its own terms
/// (what it does about it: "the model is not written", "Simbody refuses them"), but what is a
/// finding, its rule and its location are the gate's, so that one defect is reported at the same
/// line and column by every tool.
///
/// The location rule: a finding points at the key that carries the defect, falling back to the
/// link itself when that key is not written.
///   - A mass (inertia-nonpositive-mass: negative, or zero on a moving link): mass_source(),
///     which for a negative mass is the contribution that makes it negative.
///   - A combined inertia (inertia-not-positive-definite, inertia-triangle, inertia-tiny):
///     inertia_source().
///   - An asymmetric tensor (inertia-asymmetric): the contribution that carries it, i.e. the
///     link's inertia key for the link-level keys, else the RigidBody node.
///   - A joint axis (joint-axis-zero, joint-axis-not-unit): the joint_axis key; a joint range
///     (joint-range-reversed, joint-range-zero-width): the joint_range key.
/// A tool that reports what it does about a finding under a rule of its own (body2mjcf's
/// export-value-changed when it balances an inertia or raises a massless moving link to its
/// floor, bodysim's dynamics-inertia-balanced) reports it at the finding's location too
/// (report_physical_as), so a massless link's floor is at its mass, a balanced tensor at its
/// inertia.

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/inertia.h>
#include <bodyfmt/model.h>

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// MuJoCo's mjMINVAL (double build): the smallest mass and principal moment mjCModel accepts
/// for a moving body, unless a body welded to it carries both.
inline constexpr double kMujocoMinVal = 1e-15;
/// A joint axis shorter than this has no direction (joint-axis-zero).
inline constexpr double kZeroAxisLength = 1e-9;
/// A joint axis whose length differs from 1 by more than this is not a unit vector
/// (joint-axis-not-unit; Choreonoid does not normalise it).
inline constexpr double kUnitAxisTolerance = 1e-6;

/// A joint that moves in a simulation: revolute, prismatic, free (also a free root).
/// Fixed and pseudo_continuous_track joints are kinematically fixed (body-format-spec §6.2).
bool is_moving(const Link& link);

/// The most specific place the mass of `link` is written: the first contribution whose mass is
/// negative (its mass key for the link-level keys, else its RigidBody node), else the mass key,
/// the first RigidBody that gives the link mass, the inertia key, the link itself.
SourceLocation mass_source(const Link& link);

enum class PhysicalDefect {
  kInertiaAsymmetric,    ///< a contribution's tensor is not symmetric within the tolerance
  kNegativeMass,         ///< the link's combined mass is negative
  kNotPositiveDefinite,  ///< a principal moment is negative (InertiaValidity::negative_moment)
  kTriangle,             ///< the principal moments violate A + B >= C (InertiaValidity::triangle)
  /// A moving link with zero mass, and no welded descendant with a mass and moments MuJoCo
  /// accepts: no engine can accelerate it.
  kMovingMassless,
  /// A moving link with a positive mass, whose mass or smallest principal moment is below
  /// kMujocoMinVal, and no welded descendant with a mass and moments MuJoCo accepts.
  kMovingBelowMinimum,
  kAxisZero,        ///< revolute, prismatic or track joint with an axis shorter than kZeroAxisLength
  kAxisNotUnit,     ///< an axis whose length differs from 1 by more than kUnitAxisTolerance
  kRangeReversed,   ///< revolute or prismatic joint with a range lower > upper
  kRangeZeroWidth,  ///< revolute or prismatic joint with a range lower == upper
};

/// The rule id of a defect in the rule table (rules.h).
std::string_view physical_rule(PhysicalDefect defect);

struct PhysicalFinding {
  PhysicalDefect defect = PhysicalDefect::kNegativeMass;
  LinkIndex link = -1;
  SourceLocation at;  ///< by the location rule above
  std::string_view rule() const { return physical_rule(defect); }

  /// kInertiaAsymmetric: the contribution (index into Link::mass_contributions), the entry
  /// (row < column) where the tensor differs most from its transpose, and that difference
  /// relative to the tensor's largest entry.
  std::size_t contribution = 0;
  int row = 0, column = 0;
  double asymmetry = 0;

  /// kNotPositiveDefinite, kTriangle: the principal decomposition of the link's combined
  /// inertia as written, its validity, and balance_inertia()'s tensor (nullopt when balancing
  /// leaves nothing). kMovingMassless, kMovingBelowMinimum: the decomposition of the inertia the
  /// link is simulated or written with (balanced under the policy).
  PrincipalInertia principal;
  InertiaValidity validity;
  std::optional<Eigen::Matrix3d> balanced;
  /// kNotPositiveDefinite, kTriangle: PhysicalOptions::balance_inertia was set, so the tool
  /// uses `balanced` (a warning of the tool's) instead of refusing the model.
  bool balanced_by_policy = false;
  /// The tensor a tool uses under the policy: `balanced`, or zero when balancing leaves nothing.
  Eigen::Matrix3d balanced_inertia() const { return balanced ? *balanced : Eigen::Matrix3d::Zero(); }
};

/// What the gate knows of each link besides its findings.
struct LinkPhysics {
  /// compute_derived could combine the link's mass properties (computable()) and the loader
  /// took every inertia as written; when not, compute_derived reported derived-not-finite (or
  /// the loader load-inertia-size) and the gate has no finding about the link's mass.
  bool computable = false;
  bool moving = false;           ///< is_moving()
  bool welded_to_world = false;  ///< not moving, and a root or fixed to a link welded to the world
  bool negative_mass = false;    ///< it has a kNegativeMass finding
  bool negative_moment = false;  ///< it has a kNotPositiveDefinite finding
  /// Computable with a mass >= 0, and an inertia that is physical or balanced by the policy.
  bool usable = false;
};

struct PhysicalOptions {
  /// The balancing policy: use balance_inertia()'s tensor for an inertia that is not physical
  /// (kNotPositiveDefinite, kTriangle findings with balanced_by_policy) instead of refusing it.
  bool balance_inertia = false;
  /// inertia-asymmetric: the largest |I - Iᵀ| entry relative to the tensor's largest entry.
  double symmetry_tolerance = 1e-6;
};

struct PhysicalVerdict {
  /// Indexed like Model::links; empty when the derived data does not match the model.
  std::vector<LinkPhysics> links;
  /// Per link, in link order: kInertiaAsymmetric (per contribution), kNegativeMass,
  /// kNotPositiveDefinite or kTriangle; then the moving-body findings (kMovingMassless,
  /// kMovingBelowMinimum) in link order; then the joint findings in link order.
  std::vector<PhysicalFinding> findings;
  /// Every link is usable: a tool that needs physical mass properties can build the model.
  bool masses_usable = false;
  /// No kAxisZero and no kRangeReversed: every joint has a direction and a range it can be in.
  bool joints_usable = true;
};

/// The gate. Mass findings need `derived` (computed by compute_derived from `model`); when its
/// mass data does not match the model there are none, and only the joints are assessed.
PhysicalVerdict assess_physical(const Model& model, const Derived& derived, const PhysicalOptions& options = {});
/// The joint half of the gate alone (kAxisZero, kAxisNotUnit, kRangeReversed, kRangeZeroWidth),
/// for a caller without derived data; assess_physical gives the same findings.
std::vector<PhysicalFinding> assess_joints(const Model& model);

/// The one way to report a finding: its rule, at its location, in the tool's words.
void report_physical(DiagnosticSink& sink, const PhysicalFinding& finding, std::string message,
                     std::string fix_hint = {});
/// A consequence of `finding` under a rule of the tool's own (e.g. export-value-changed), at the
/// finding's location.
void report_physical_as(DiagnosticSink& sink, std::string_view rule_id, const PhysicalFinding& finding,
                        std::string message, std::string fix_hint = {});

}  // namespace bodyfmt
#pragma GCC visibility pop
