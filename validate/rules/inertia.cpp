// Inertia rules (issue 4, "Inertia"): what MuJoCo, Drake and gz-math refuse, with their
// tolerances (shared/spec/anchors.md §2), plus two plausibility warnings.

#include "rule_context.h"

#include <bodyfmt/inertia.h>

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <vector>

namespace bodyfmt::validate::detail {
namespace {

// MuJoCo's mjMINVAL (include/mujoco/mjtype.h, double build).
constexpr double kMjMinVal = 1e-15;

// The balanced tensor as the fix hint, in the 6-element form [Ixx, Ixy, Ixz, Iyy, Iyz, Izz].
std::string nearest_valid(const Eigen::Matrix3d& inertia) {
  const std::optional<Eigen::Matrix3d> balanced = balance_inertia(inertia);
  if (!balanced) return {};
  const Eigen::Matrix3d& I = *balanced;
  return fmt::format("nearest valid inertia (link axes, about the centre of mass): [{}, {}, {}, {}, {}, {}]",
                     num(I(0, 0)), num(I(0, 1)), num(I(0, 2)), num(I(1, 1)), num(I(1, 2)), num(I(2, 2)));
}

// The most specific place a link's mass is written (inertia_source() for its inertia).
SourceLocation mass_location(const Link& link) {
  return first_known({link.sources.mass(), rigid_body_source(link), link.sources.inertia(), link.source});
}

/// Per link: welded to the world (a fixed root and its fixed descendants, e.g. floors). One
/// pass in depth-first order, parents before children, instead of a walk to the root per link.
std::vector<bool> welded_to_world(const Model& model) {
  std::vector<bool> welded(model.links.size(), false);
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    welded[i] = !is_moving(link) && (link.parent < 0 || welded[static_cast<std::size_t>(link.parent)]);
  }
  return welded;
}

void check_symmetry(const RuleContext& ctx, const Link& link) {
  for (const MassContribution& c : link.mass_contributions) {
    const Eigen::Matrix3d& I = c.inertia;
    const double scale = I.cwiseAbs().maxCoeff();
    if (scale == 0) continue;
    const Eigen::Matrix3d skew = I - I.transpose();
    Eigen::Index row = 0, col = 0;
    const double worst = skew.cwiseAbs().maxCoeff(&row, &col);
    if (worst <= ctx.options.inertia_symmetry_tolerance * scale) continue;
    if (row > col) std::swap(row, col);
    const char* axis = "xyz";
    const SourceLocation at = c.from_link_keys ? first_known({link.sources.inertia(), c.source, link.source})
                                               : first_known({c.source, link.source});
    ctx.report("inertia-asymmetric", at,
               fmt::format("inertia of link \"{}\" is not symmetric: I{}{} = {} but I{}{} = {} (relative "
                           "difference {} > {})",
                           link.name, axis[row], axis[col], num(I(row, col)), axis[col], axis[row], num(I(col, row)),
                           num(worst / scale), num(ctx.options.inertia_symmetry_tolerance)),
               "write the 6-element form [Ixx, Ixy, Ixz, Iyy, Iyz, Izz]; Choreonoid uses the 9 numbers as given");
  }
}

// Moments and mass that MuJoCo accepts for a moving body (mjCBody::Compile).
bool mujoco_valid(double mass, const PrincipalInertia& p) { return mass >= kMjMinVal && p.moments[0] >= kMjMinVal; }

void check_link(const RuleContext& ctx, LinkIndex index, bool welded) {
  const Link& link = ctx.model.links[index];
  check_symmetry(ctx, link);
  if (link.mass_contributions.empty()) return;  // Choreonoid's defaults (load-default-mass)
  const MassProperties& mp = ctx.derived.mass[index];
  const PrincipalInertia p = principal_inertia(mp.inertia);
  const double trace = p.moments.sum();
  const SourceLocation at = inertia_source(link);
  // Formatted only for a finding: most links have none.
  const auto moments = [&] {
    return fmt::format("({}, {}, {})", num(p.moments[0]), num(p.moments[1]), num(p.moments[2]));
  };

  // Negative mass is wrong anywhere; zero mass only where the link moves on its own.
  if (mp.mass < 0) {
    ctx.report("inertia-nonpositive-mass", mass_location(link),
               fmt::format("link \"{}\" has negative mass {} kg", link.name, num(mp.mass)),
               "mass must be positive; MuJoCo silently clamps it to 0, Drake and gz-math refuse it");
  }

  // Drake's tolerance for a negative moment, ε = 16·DBL_EPSILON·max(1, tr/2).
  const double drake_eps = 16 * DBL_EPSILON * std::max(1.0, std::abs(trace) / 2);
  const double gz_eps = 10 * DBL_EPSILON * std::abs(trace) / 2;
  const InertiaValidity validity = inertia_validity(p);
  const bool semidefinite = !validity.negative_moment;
  if (validity.negative_moment) {
    ctx.report("inertia-not-positive-definite", at,
               fmt::format("inertia of link \"{}\" has a negative principal moment: principal moments {}", link.name,
                           moments()),
               nearest_valid(mp.inertia));
  }
  if (validity.triangle) {
    const double margin = validity.triangle_margin;
    std::vector<std::string> refuse = {"MuJoCo (A + B >= C, no tolerance)"};
    if (margin < -drake_eps) refuse.push_back(fmt::format("Drake (tolerance 16ε·max(1, tr/2) = {})", num(drake_eps)));
    if (margin < -gz_eps) refuse.push_back(fmt::format("gz-math (tolerance 10ε·tr/2 = {})", num(gz_eps)));
    ctx.report("inertia-triangle", at,
               fmt::format("principal moments {} of link \"{}\" violate the triangle inequality: {} + {} - {} = "
                           "{}; refused by {}",
                           moments(), link.name, num(p.moments[0]), num(p.moments[1]), num(p.moments[2]), num(margin),
                           fmt::join(refuse, ", ")),
               nearest_valid(mp.inertia));
  }

  // The two plausibility warnings only for links that can move: the mass data of a link welded
  // to the world (a fixed root and its fixed descendants, e.g. floors) is never simulated.
  const BoundingBox box = geometry_bounds(ctx.derived, index);
  if (mp.mass > 0 && !box.empty() && !welded) {
    // CoM outside the geometry box, enlarged by 1% of its diagonal (and 1 mm) for rounding.
    const double slack = 0.01 * (box.max - box.min).norm() + 1e-3;
    const Eigen::Vector3d& c = mp.center_of_mass;
    if ((c.array() < box.min.array() - slack).any() || (c.array() > box.max.array() + slack).any()) {
      ctx.report("inertia-com-outside", first_known({link.sources.center_of_mass(), at}),
                 fmt::format("centre of mass {} of link \"{}\" lies outside its geometry bounds {} .. {}", vec(c),
                             link.name, vec(box.min), vec(box.max)));
    }
    // Compare traces with a solid box of the same mass filling the geometry bounds:
    // tr = m/6 (dx² + dy² + dz²). Mass at the corners gives 3x that, so a real body is
    // rarely more than a few times away.
    const Eigen::Vector3d d = box.max - box.min;
    const double box_trace = mp.mass / 6 * d.squaredNorm();
    const double factor = ctx.options.inertia_plausibility_factor;
    if (box_trace > 0 && trace > 0 && semidefinite) {
      const double ratio = trace / box_trace;
      if (ratio > factor || ratio < 1 / factor) {
        ctx.report("inertia-implausible", at,
                   fmt::format("inertia of link \"{}\" is {} times that of a solid box of its mass ({} kg) filling "
                               "its geometry bounds {} (trace {} vs {} kg·m²; factor {})",
                               link.name, num(ratio), num(mp.mass), vec(d), num(trace), num(box_trace), num(factor)));
      }
    }
  }
}

// MuJoCo refuses a moving body whose mass or a principal moment is below mjMINVAL unless a
// static (welded) descendant has valid ones; massless moving links need that descendant too.
/// Per link: a static (welded) descendant with mass and moments MuJoCo accepts. One pass in
/// reverse depth-first order, children before parents, without recursion.
std::vector<bool> valid_welded_descendant(const Model& model, const Derived& derived) {
  std::vector<bool> found(model.links.size(), false);
  for (std::size_t k = model.links.size(); k-- > 0;) {
    const Link& c = model.links[k];
    if (c.parent < 0 || is_moving(c)) continue;
    if (found[k] || mujoco_valid(derived.mass[k].mass, principal_inertia(derived.mass[k].inertia)))
      found[static_cast<std::size_t>(c.parent)] = true;
  }
  return found;
}

void check_moving(const RuleContext& ctx, LinkIndex index, bool has_valid_welded_descendant) {
  const Link& link = ctx.model.links[index];
  if (!is_moving(link)) return;
  const MassProperties& mp = ctx.derived.mass[index];
  if (mp.mass < 0) return;  // reported above
  const PrincipalInertia p = principal_inertia(mp.inertia);
  if (mujoco_valid(mp.mass, p) || has_valid_welded_descendant) return;
  const std::string joint = index == 0 ? "the free root" : fmt::format("a {} joint", joint_type_name(link.joint_type));
  if (mp.mass == 0) {
    ctx.report(
        "inertia-nonpositive-mass", mass_location(link),
        fmt::format("link \"{}\" moves ({}) but has zero mass, and no fixed child carries mass", link.name, joint),
        "give the link its mass and inertia; MuJoCo, Drake and Choreonoid's AIST simulator need it");
    return;
  }
  if (p.moments[0] < 0) return;  // inertia-not-positive-definite
  ctx.report("inertia-tiny", inertia_source(link),
             fmt::format("link \"{}\" moves ({}) but its mass {} kg or smallest principal moment {} kg·m² is below "
                         "MuJoCo's mjMINVAL {}",
                         link.name, joint, num(mp.mass), num(p.moments[0]), num(kMjMinVal)),
             "MuJoCo refuses moving bodies with a mass or principal moment below 1e-15");
}

}  // namespace

void check_inertia(const RuleContext& ctx) {
  if (ctx.derived.mass.size() != ctx.model.links.size()) return;
  const std::vector<bool> welded = welded_to_world(ctx.model);
  const std::vector<bool> valid_descendant = valid_welded_descendant(ctx.model, ctx.derived);
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(ctx.model.links.size()); ++i) {
    // A link whose mass properties are not computable was reported by compute_derived
    // (derived-not-finite); its NaN moments would only add findings that follow from it.
    if (!computable(ctx.derived.mass[static_cast<std::size_t>(i)])) {
      check_symmetry(ctx, ctx.model.links[static_cast<std::size_t>(i)]);
      continue;
    }
    check_link(ctx, i, welded[static_cast<std::size_t>(i)]);
    check_moving(ctx, i, valid_descendant[static_cast<std::size_t>(i)]);
  }
}

}  // namespace bodyfmt::validate::detail
