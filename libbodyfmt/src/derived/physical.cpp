#include <bodyfmt/physical.h>
#include <bodyfmt/rules.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace bodyfmt {

bool is_moving(const Link& link) {
  return link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic ||
         link.joint_type == JointType::kFree;
}

SourceLocation mass_source(const Link& link) {
  for (const MassContribution& c : link.mass_contributions) {
    if (!(c.mass < 0)) continue;
    return c.from_link_keys ? first_known({link.sources.mass(), c.source, link.source})
                            : first_known({c.source, link.source});
  }
  return first_known({link.sources.mass(), rigid_body_source(link), link.sources.inertia(), link.source});
}

std::string_view physical_rule(PhysicalDefect defect) {
  switch (defect) {
    case PhysicalDefect::kInertiaAsymmetric: return "inertia-asymmetric";
    case PhysicalDefect::kNegativeMass: return "inertia-nonpositive-mass";
    case PhysicalDefect::kNotPositiveDefinite: return "inertia-not-positive-definite";
    case PhysicalDefect::kTriangle: return "inertia-triangle";
    case PhysicalDefect::kMovingMassless: return "inertia-nonpositive-mass";
    case PhysicalDefect::kMovingBelowMinimum: return "inertia-tiny";
    case PhysicalDefect::kAxisZero: return "joint-axis-zero";
    case PhysicalDefect::kAxisNotUnit: return "joint-axis-not-unit";
    case PhysicalDefect::kRangeReversed: return "joint-range-reversed";
    case PhysicalDefect::kRangeZeroWidth: return "joint-range-zero-width";
  }
  return "internal-error";
}

namespace {

PhysicalFinding finding(PhysicalDefect defect, LinkIndex link, SourceLocation at) {
  PhysicalFinding f;
  f.defect = defect;
  f.link = link;
  f.at = std::move(at);
  return f;
}

void assess_symmetry(const Link& link, LinkIndex index, double tolerance, std::vector<PhysicalFinding>& out) {
  for (std::size_t k = 0; k < link.mass_contributions.size(); ++k) {
    const MassContribution& c = link.mass_contributions[k];
    const Eigen::Matrix3d& I = c.inertia;
    const double scale = I.cwiseAbs().maxCoeff();
    if (scale == 0) continue;
    const Eigen::Matrix3d skew = I - I.transpose();
    Eigen::Index row = 0, col = 0;
    const double worst = skew.cwiseAbs().maxCoeff(&row, &col);
    if (worst <= tolerance * scale) continue;
    if (row > col) std::swap(row, col);
    PhysicalFinding f = finding(PhysicalDefect::kInertiaAsymmetric, index,
                                c.from_link_keys ? first_known({link.sources.inertia(), c.source, link.source})
                                                 : first_known({c.source, link.source}));
    f.contribution = k;
    f.row = static_cast<int>(row);
    f.column = static_cast<int>(col);
    f.asymmetry = worst / scale;
    out.push_back(std::move(f));
  }
}

// Mass and moments MuJoCo accepts for a moving body (mjCBody::Compile).
bool mujoco_accepts(double mass, const PrincipalInertia& p) {
  return mass >= kMujocoMinVal && p.moments[0] >= kMujocoMinVal;
}

}  // namespace

std::vector<PhysicalFinding> assess_joints(const Model& model) {
  std::vector<PhysicalFinding> out;
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(model.links.size()); ++i) {
    const Link& link = model.links[static_cast<std::size_t>(i)];
    if (is_one_dof(link) || link.joint_type == JointType::kPseudoContinuousTrack) {
      const double norm = link.joint_axis.norm();
      if (norm < kZeroAxisLength)
        out.push_back(finding(PhysicalDefect::kAxisZero, i, source_of(link, LinkSources::kJointAxis)));
      else if (std::abs(norm - 1) > kUnitAxisTolerance)
        out.push_back(finding(PhysicalDefect::kAxisNotUnit, i, source_of(link, LinkSources::kJointAxis)));
    }
    if (is_one_dof(link)) {
      if (link.joint_range_lower > link.joint_range_upper)
        out.push_back(finding(PhysicalDefect::kRangeReversed, i, source_of(link, LinkSources::kJointRange)));
      else if (link.joint_range_lower == link.joint_range_upper)
        out.push_back(finding(PhysicalDefect::kRangeZeroWidth, i, source_of(link, LinkSources::kJointRange)));
    }
  }
  return out;
}

PhysicalVerdict assess_physical(const Model& model, const Derived& derived, const PhysicalOptions& options) {
  PhysicalVerdict verdict;
  const std::size_t n = model.links.size();
  if (derived.mass.size() == n) {
    verdict.links.resize(n);
    verdict.masses_usable = true;
    // Per link: the mass and moments it is used with satisfy MuJoCo; and the index of its
    // balanced finding under the policy, whose tensor it is used with.
    std::vector<bool> accepted(n, false);
    std::vector<std::size_t> balanced_by(n, SIZE_MAX);
    for (std::size_t i = 0; i < n; ++i) {
      const Link& link = model.links[i];
      const LinkIndex index = static_cast<LinkIndex>(i);
      LinkPhysics& lp = verdict.links[i];
      lp.moving = is_moving(link);
      lp.welded_to_world =
          !lp.moving && (link.parent < 0 || verdict.links[static_cast<std::size_t>(link.parent)].welded_to_world);
      assess_symmetry(link, index, options.symmetry_tolerance, verdict.findings);
      const MassProperties& mp = derived.mass[i];
      // An inertia the loader refused (load-inertia-size) is judged by no rule: the tensor in its
      // place was never written.
      const bool refused = std::any_of(link.mass_contributions.begin(), link.mass_contributions.end(),
                                       [](const MassContribution& c) { return c.inertia_refused; });
      lp.computable = computable(mp) && !refused;
      if (!lp.computable) {  // compute_derived reported it (derived-not-finite), or the loader did
        verdict.masses_usable = false;
        continue;
      }
      lp.usable = true;
      if (mp.mass < 0) {
        verdict.findings.push_back(finding(PhysicalDefect::kNegativeMass, index, mass_source(link)));
        lp.negative_mass = true;
        lp.usable = false;
      }
      const PrincipalInertia p = principal_inertia(mp.inertia);
      const InertiaValidity validity = inertia_validity(p);
      accepted[i] = mujoco_accepts(mp.mass, p);
      if (!validity.valid()) {
        PhysicalFinding f =
            finding(validity.negative_moment ? PhysicalDefect::kNotPositiveDefinite : PhysicalDefect::kTriangle, index,
                    inertia_source(link));
        lp.negative_moment = validity.negative_moment;
        f.principal = p;
        f.validity = validity;
        f.balanced = balance_inertia(mp.inertia);
        f.balanced_by_policy = options.balance_inertia;
        if (options.balance_inertia) {
          balanced_by[i] = verdict.findings.size();
          accepted[i] = mujoco_accepts(mp.mass, principal_inertia(f.balanced_inertia()));
        } else {
          lp.usable = false;
        }
        verdict.findings.push_back(std::move(f));
      }
      verdict.masses_usable = verdict.masses_usable && lp.usable;
    }

    // MuJoCo refuses a moving body whose mass or a principal moment is below mjMINVAL unless a
    // static (welded) descendant has valid ones. Per link: such a descendant exists. One pass
    // in reverse depth-first order (children before parents), without recursion.
    std::vector<bool> carried(n, false);
    for (std::size_t k = n; k-- > 0;) {
      const Link& c = model.links[k];
      if (c.parent < 0 || verdict.links[k].moving) continue;
      if (carried[k] || accepted[k]) carried[static_cast<std::size_t>(c.parent)] = true;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const MassProperties& mp = derived.mass[i];
      if (!verdict.links[i].moving || !verdict.links[i].computable || mp.mass < 0 || accepted[i] || carried[i])
        continue;
      const Link& link = model.links[i];
      const bool massless = mp.mass == 0;
      PhysicalFinding f = finding(massless ? PhysicalDefect::kMovingMassless : PhysicalDefect::kMovingBelowMinimum,
                                  static_cast<LinkIndex>(i), massless ? mass_source(link) : inertia_source(link));
      f.principal = balanced_by[i] == SIZE_MAX ? principal_inertia(mp.inertia)
                                               : principal_inertia(verdict.findings[balanced_by[i]].balanced_inertia());
      verdict.findings.push_back(std::move(f));
    }
  }

  std::vector<PhysicalFinding> joints = assess_joints(model);
  for (PhysicalFinding& f : joints) {
    if (f.defect == PhysicalDefect::kAxisZero || f.defect == PhysicalDefect::kRangeReversed)
      verdict.joints_usable = false;
    verdict.findings.push_back(std::move(f));
  }
  return verdict;
}

void report_physical(DiagnosticSink& sink, const PhysicalFinding& finding, std::string message, std::string fix_hint) {
  report_rule(sink, finding.rule(), finding.at, std::move(message), std::move(fix_hint));
}

void report_physical_as(DiagnosticSink& sink, std::string_view rule_id, const PhysicalFinding& finding,
                        std::string message, std::string fix_hint) {
  report_rule(sink, rule_id, finding.at, std::move(message), std::move(fix_hint));
}

}  // namespace bodyfmt
