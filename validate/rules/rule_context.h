#pragma once
// Shared helpers for the rule families in validate/rules/. Internal: not installed.

#include <bodyfmt/angles.h>
#include <bodyfmt/physical.h>
#include <bodyfmt/validate.h>

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

namespace bodyfmt::validate::detail {

/// What every rule family reads, plus report() which takes the severity from the rule table.
struct RuleContext {
  const Model& model;
  const Derived& derived;
  const CheckOptions& options;
  DiagnosticSink& sink;
  /// The physical-validity gate's verdict (bodyfmt/physical.h): the inertia and joint rules
  /// report its findings.
  const PhysicalVerdict& physical;

  /// Reports `rule_id` with its default severity from the rule table (asserts the row exists).
  void report(std::string_view rule_id, const SourceLocation& location, std::string message,
              std::string fix_hint = {}) const;
  /// Reports a finding of the gate: its rule, at its location.
  void report(const PhysicalFinding& finding, std::string message, std::string fix_hint = {}) const {
    report(finding.rule(), finding.at, std::move(message), std::move(fix_hint));
  }
};

/// A number for messages (bodyfmt/readable_number.h): 6 significant digits, no trailing zeros.
std::string num(double value);
/// "[a, b, c]".
std::string vec(const Eigen::Vector3d& v);
/// A limit for messages: a number, or "unlimited" for the sentinel.
std::string limit(double value);

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
