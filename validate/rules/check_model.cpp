#include "rule_context.h"

#include <bodyfmt/readable_number.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

#include <cassert>
#include <cmath>

namespace bodyfmt::validate {
namespace detail {

void RuleContext::report(std::string_view rule_id, const SourceLocation& location, std::string message,
                         std::string fix_hint) const {
  SourceLocation at = location.known() || !location.file.empty() ? location : model.source;
  if (at.file.empty()) at.file = model.source_file;
  report_rule(sink, rule_id, std::move(at), std::move(message), std::move(fix_hint));
}

std::string num(double value) { return readable_number(value); }

std::string vec(const Eigen::Vector3d& v) { return fmt::format("[{}, {}, {}]", num(v.x()), num(v.y()), num(v.z())); }

std::string limit(double value) {
  if (std::abs(value) >= kUnlimited) return value < 0 ? "-unlimited" : "unlimited";
  return num(value);
}

BoundingBox geometry_bounds(const Derived& derived, LinkIndex link) {
  BoundingBox box;
  if (link >= 0 && static_cast<std::size_t>(link) < derived.bounds.size()) {
    box.add(derived.bounds[link].visual);
    box.add(derived.bounds[link].collision);
  }
  return box;
}

}  // namespace detail

void check_model(const Model& model, const Derived& derived, const CheckOptions& options, DiagnosticSink& sink) {
  if (model.links.empty()) return;
  PhysicalOptions physical_options;
  physical_options.symmetry_tolerance = options.inertia_symmetry_tolerance;
  const PhysicalVerdict physical = assess_physical(model, derived, physical_options);
  const detail::RuleContext ctx{model, derived, options, sink, physical};
  detail::check_structure(ctx);
  detail::check_joints(ctx);
  detail::check_units(ctx);
  detail::check_inertia(ctx);
  detail::check_geometry(ctx);
  detail::check_resources(ctx);
  detail::check_devices(ctx);
}

}  // namespace bodyfmt::validate
