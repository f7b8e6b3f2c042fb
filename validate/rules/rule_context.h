#pragma once
// Shared helpers for the rule families in validate/rules/. Internal: not installed.

#include <bodyfmt/validate.h>

#include <initializer_list>
#include <string>
#include <string_view>

namespace bodyfmt::validate::detail {

constexpr double kPi = 3.14159265358979323846;

/// What every rule family reads, plus report() which takes the severity from the rule table.
struct RuleContext {
  const Model& model;
  const Derived& derived;
  const CheckOptions& options;
  DiagnosticSink& sink;

  /// Reports `rule_id` with its default severity from the rule table (asserts the row exists).
  void report(std::string_view rule_id, const SourceLocation& location, std::string message,
              std::string fix_hint = {}) const;
};

/// Shortest round-trip-ish form for messages: 6 significant digits, no trailing zeros.
std::string num(double value);
/// "[a, b, c]".
std::string vec(const Eigen::Vector3d& v);
/// A limit for messages: a number, or "unlimited" for the sentinel.
std::string limit(double value);

/// A joint that moves in a simulation: revolute, prismatic, free (also a free root).
/// Fixed and pseudo_continuous_track joints are kinematically fixed (body-format-spec §6.2).
bool is_moving(const Link& link);

/// Joint types whose axis and range mean something: revolute, prismatic.
bool is_one_dof(const Link& link);

/// The union of a link's visual and collision boxes (tight, link frame); empty when none.
BoundingBox geometry_bounds(const Derived& derived, LinkIndex link);

void check_inertia(const RuleContext& ctx);
void check_joints(const RuleContext& ctx);
void check_units(const RuleContext& ctx);
void check_structure(const RuleContext& ctx);
void check_geometry(const RuleContext& ctx);
void check_resources(const RuleContext& ctx);
void check_devices(const RuleContext& ctx);

}  // namespace bodyfmt::validate::detail
