// Inertia rules (issue 4, "Inertia"): what MuJoCo, Drake and gz-math refuse, with their
// tolerances (shared/spec/anchors.md §2), plus two plausibility warnings.

#include "rule_context.h"

#include <bodyfmt/inertia.h>

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace bodyfmt::validate::detail {
namespace {

// The balanced tensor as the fix hint, in the 6-element form [Ixx, Ixy, Ixz, Iyy, Iyz, Izz].
std::string nearest_valid(const PhysicalFinding& f) {
  if (!f.balanced) return {};
  const Eigen::Matrix3d& I = *f.balanced;
  return fmt::format("nearest valid inertia (link axes, about the centre of mass): [{}, {}, {}, {}, {}, {}]",
                     num(I(0, 0)), num(I(0, 1)), num(I(0, 2)), num(I(1, 1)), num(I(1, 2)), num(I(2, 2)));
}

std::string moments_text(const PrincipalInertia& p) {
  return fmt::format("({}, {}, {})", num(p.moments[0]), num(p.moments[1]), num(p.moments[2]));
}

void report_asymmetric(const RuleContext& ctx, const PhysicalFinding& f) {
  const Link& link = ctx.model.links[static_cast<std::size_t>(f.link)];
  const Eigen::Matrix3d& I = link.mass_contributions[f.contribution].inertia;
  const char* axis = "xyz";
  const int row = f.row, col = f.column;
  ctx.report(f,
             fmt::format("inertia of link \"{}\" is not symmetric: I{}{} = {} but I{}{} = {} (relative "
                         "difference {} > {})",
                         link.name, axis[row], axis[col], num(I(row, col)), axis[col], axis[row], num(I(col, row)),
                         num(f.asymmetry), num(ctx.options.inertia_symmetry_tolerance)),
             "write the 6-element form [Ixx, Ixy, Ixz, Iyy, Iyz, Izz]; Choreonoid uses the 9 numbers as given");
}

// The hint of a tensor no engine takes: recompute it from the shapes where the link has any,
// else the nearest valid one. Which engines refuse it, with their tolerances, is the rule's
// documentation (`bodycheck --explain RULE`), not every finding's.
std::string recompute_hint(const RuleContext& ctx, const PhysicalFinding& f) {
  const std::string nearest = nearest_valid(f);
  if (geometry_bounds(ctx.derived, f.link).empty()) return nearest;
  return "compute it from the link's shapes with bodycheck --fix=geometry" +
         (nearest.empty() ? "" : "; or use the " + nearest);
}

void report_triangle(const RuleContext& ctx, const PhysicalFinding& f) {
  const Link& link = ctx.model.links[static_cast<std::size_t>(f.link)];
  const PrincipalInertia& p = f.principal;
  const double margin = f.validity.triangle_margin;
  // "0.1 + 0.1 < 0.5" where 6 digits show it; the margin where they round it away (1 + 1 < 2).
  const auto shown = [](double v) { return std::strtod(num(v).c_str(), nullptr); };
  const std::string why = shown(p.moments[0]) + shown(p.moments[1]) < shown(p.moments[2])
                              ? fmt::format("{} + {} < {}", num(p.moments[0]), num(p.moments[1]), num(p.moments[2]))
                              : fmt::format("A + B - C = {}", num(margin));
  // Every engine refuses the usual violation; one within an engine's rounding tolerance is
  // worth a clause (the tolerances themselves are the rule's documentation, --explain).
  const double trace = p.moments.sum();
  std::vector<std::string> accept;
  if (margin >= -16 * DBL_EPSILON * std::max(1.0, std::abs(trace) / 2)) accept.push_back("Drake's");
  if (margin >= -10 * DBL_EPSILON * std::abs(trace) / 2) accept.push_back("gz-math's");
  const std::string within = accept.empty() ? std::string()
                                            : fmt::format("; within {} rounding tolerance{}, so MuJoCo refuses it",
                                                          fmt::join(accept, " and "), accept.size() == 1 ? "" : "s");
  ctx.report(f,
             fmt::format("inertia of link \"{}\" is impossible for a rigid body: principal moments {} break the "
                         "triangle inequality ({}){}",
                         link.name, moments_text(p), why, within),
             recompute_hint(ctx, f));
}

void report_moving(const RuleContext& ctx, const PhysicalFinding& f) {
  const Link& link = ctx.model.links[static_cast<std::size_t>(f.link)];
  const std::string joint = f.link == 0 ? "the free root" : fmt::format("a {} joint", joint_type_name(link.joint_type));
  if (f.defect == PhysicalDefect::kMovingMassless) {
    ctx.report(
        f, fmt::format("link \"{}\" moves ({}) but has zero mass, and no fixed child carries mass", link.name, joint),
        "give the link its mass and inertia; MuJoCo, Drake and Choreonoid's AIST simulator need it");
    return;
  }
  // A negative moment is inertia-not-positive-definite's (or within its tolerance).
  if (f.principal.moments[0] < 0) return;
  const double mass = ctx.derived.mass[static_cast<std::size_t>(f.link)].mass;
  ctx.report(f,
             fmt::format("link \"{}\" moves ({}) but its mass {} kg or smallest principal moment {} kg·m² is below "
                         "MuJoCo's mjMINVAL {}",
                         link.name, joint, num(mass), num(f.principal.moments[0]), num(kMujocoMinVal)),
             "MuJoCo refuses moving bodies with a mass or principal moment below 1e-15");
}

void report_finding(const RuleContext& ctx, const PhysicalFinding& f) {
  const Link& link = ctx.model.links[static_cast<std::size_t>(f.link)];
  switch (f.defect) {
    case PhysicalDefect::kInertiaAsymmetric: report_asymmetric(ctx, f); return;
    case PhysicalDefect::kNegativeMass:
      ctx.report(f,
                 fmt::format("link \"{}\" has negative mass {} kg", link.name,
                             num(ctx.derived.mass[static_cast<std::size_t>(f.link)].mass)),
                 "mass must be positive; MuJoCo silently clamps it to 0, Drake and gz-math refuse it");
      return;
    case PhysicalDefect::kNotPositiveDefinite:
      ctx.report(f,
                 fmt::format("inertia of link \"{}\" has a negative principal moment: principal moments {}", link.name,
                             moments_text(f.principal)),
                 recompute_hint(ctx, f));
      return;
    case PhysicalDefect::kTriangle: report_triangle(ctx, f); return;
    case PhysicalDefect::kMovingMassless:
    case PhysicalDefect::kMovingBelowMinimum: report_moving(ctx, f); return;
    default: return;  // the joint rules' (joints.cpp)
  }
}

// Two plausibility warnings, only for links that can move: the mass data of a link welded to
// the world (a fixed root and its fixed descendants, e.g. floors) is never simulated.
void check_plausibility(const RuleContext& ctx, LinkIndex index) {
  const Link& link = ctx.model.links[static_cast<std::size_t>(index)];
  const LinkPhysics& physics = ctx.physical.links[static_cast<std::size_t>(index)];
  if (link.mass_contributions.empty() || !physics.computable || physics.welded_to_world) return;
  const MassProperties& mp = ctx.derived.mass[static_cast<std::size_t>(index)];
  const BoundingBox box = geometry_bounds(ctx.derived, index);
  if (!(mp.mass > 0) || box.empty()) return;
  const SourceLocation at = inertia_source(link);
  // CoM outside the geometry box, enlarged by 1% of its diagonal (and 1 mm) for rounding.
  const double slack = 0.01 * (box.max - box.min).norm() + 1e-3;
  const Eigen::Vector3d& c = mp.center_of_mass;
  if ((c.array() < box.min.array() - slack).any() || (c.array() > box.max.array() + slack).any()) {
    ctx.report("inertia-com-outside", first_known({link.sources.center_of_mass(), at}),
               fmt::format("centre of mass {} of link \"{}\" lies outside its geometry bounds {} .. {}", vec(c),
                           link.name, vec(box.min), vec(box.max)),
               "compute it from the link's shapes with bodycheck --fix=geometry");
  }
  // Compare traces with a solid box of the same mass filling the geometry bounds:
  // tr = m/6 (dx² + dy² + dz²). Mass at the corners gives 3x that, so a real body is
  // rarely more than a few times away.
  const double trace = principal_inertia(mp.inertia).moments.sum();
  const Eigen::Vector3d d = box.max - box.min;
  const double box_trace = mp.mass / 6 * d.squaredNorm();
  const double factor = ctx.options.inertia_plausibility_factor;
  if (box_trace > 0 && trace > 0 && !physics.negative_moment) {
    const double ratio = trace / box_trace;
    if (ratio > factor || ratio < 1 / factor) {
      ctx.report("inertia-implausible", at,
                 fmt::format("inertia of link \"{}\" is {} times that of a solid box of its mass ({} kg) filling "
                             "its geometry bounds {} (trace {} vs {} kg·m²; factor {})",
                             link.name, num(ratio), num(mp.mass), vec(d), num(trace), num(box_trace), num(factor)),
                 "compute it from the link's shapes with bodycheck --fix=geometry");
    }
  }
}

}  // namespace

// What is physical is the gate's (bodyfmt/physical.h); these rules word its findings and add
// the plausibility warnings.
void check_inertia(const RuleContext& ctx) {
  if (ctx.physical.links.size() != ctx.model.links.size()) return;
  for (const PhysicalFinding& f : ctx.physical.findings) report_finding(ctx, f);
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(ctx.model.links.size()); ++i) check_plausibility(ctx, i);
}

}  // namespace bodyfmt::validate::detail
