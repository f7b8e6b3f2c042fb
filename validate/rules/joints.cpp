// Joint rules (issue 4, "Joints"): ids as Choreonoid's StdBodyLoader numbers them, axes it
// does not normalise, ranges and velocity limits it accepts silently (body-format-spec §15).

#include "rule_context.h"

#include <fmt/format.h>

#include <map>
#include <vector>

namespace bodyfmt::validate::detail {
namespace {

void check_ids(const RuleContext& ctx) {
  std::map<int, LinkIndex> first;
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(ctx.model.links.size()); ++i) {
    const Link& link = ctx.model.links[i];
    if (link.joint_id < 0) continue;
    const SourceLocation at = source_of(link, LinkSources::kJointId);
    if (link.joint_type == JointType::kFixed) {
      ctx.report("joint-id-on-fixed", at,
                 fmt::format("link \"{}\" has joint_id {} but its joint is fixed", link.name, link.joint_id),
                 "remove joint_id, or give the link a joint_type; Choreonoid still counts the id in numJoints");
    }
    auto [it, inserted] = first.emplace(link.joint_id, i);
    // The links of one ContinuousTrack node (each the child of the one before, all read from
    // that node) share its id as Choreonoid loads them; the loader says so
    // (load-track-shared-joint).
    const bool track_clone = link.parent >= 0 && ctx.model.links[link.parent].source == link.source;
    if (!inserted && !track_clone) {
      const Link& other = ctx.model.links[it->second];
      ctx.report("joint-id-duplicate", at,
                 fmt::format("joint_id {} of link \"{}\" is already used by link \"{}\" (line {})", link.joint_id,
                             link.name, other.name, other.sources.joint_id().line),
                 "give every joint its own id; Choreonoid keeps only one joint per id");
    }
  }
  if (first.empty()) return;
  // Choreonoid warns "Joint ID n is not specified" for every unused id below the largest.
  // Counted, not listed: an id of 2^31 - 1 must not make a list of two billion numbers.
  constexpr std::size_t kShown = 20;
  std::vector<long long> shown;
  long long missing = 0;
  LinkIndex after_gap = -1;
  long long expected = 0;
  for (const auto& [id, index] : first) {
    if (id > expected && after_gap < 0) after_gap = index;
    if (id > expected) {
      for (long long k = expected; k < id && shown.size() < kShown; ++k) shown.push_back(k);
      missing += id - expected;
    }
    expected = static_cast<long long>(id) + 1;
  }
  if (missing == 0) return;
  const Link& link = ctx.model.links[after_gap];
  std::string list = fmt::format("{}", fmt::join(shown, ", "));
  if (static_cast<long long>(shown.size()) < missing) list += fmt::format(", ... ({} in all)", missing);
  ctx.report("joint-id-gap", source_of(link, LinkSources::kJointId),
             fmt::format("joint ids are not contiguous: {} {} missing below the largest id {}", list,
                         missing == 1 ? "is" : "are", first.rbegin()->first),
             "number the joints 0..n-1; Choreonoid reserves a joint slot for every missing id");
}

// Axis and range: what is usable is the gate's (bodyfmt/physical.h); these rules word it.
void report_axis(const RuleContext& ctx, const PhysicalFinding& f, const Link& link) {
  if (f.defect == PhysicalDefect::kAxisZero) {
    ctx.report(f, fmt::format("joint axis of link \"{}\" is the zero vector {}", link.name, vec(link.joint_axis)),
               "give the axis a direction, e.g. joint_axis: Z");
    return;
  }
  const double norm = link.joint_axis.norm();
  ctx.report(f,
             fmt::format("joint axis {} of link \"{}\" has length {}; Choreonoid does not normalise it, so "
                         "velocities and displacements are scaled by it",
                         vec(link.joint_axis), link.name, num(norm)),
             fmt::format("joint_axis: {}", vec(link.joint_axis / norm)));
}

void report_range(const RuleContext& ctx, const PhysicalFinding& f, const Link& link) {
  const double lo = link.joint_range_lower, hi = link.joint_range_upper;
  const bool revolute = link.joint_type == JointType::kRevolute;
  const double shown = revolute && ctx.model.angles_in_degrees ? 180 / kPi : 1.0;
  const char* unit = revolute ? (ctx.model.angles_in_degrees ? " deg" : " rad") : " m";
  auto written = [&](double v) { return std::abs(v) >= kUnlimited ? limit(v) : num(v * shown) + unit; };
  if (f.defect == PhysicalDefect::kRangeReversed) {
    ctx.report(
        f,
        fmt::format("joint range of link \"{}\" is reversed: lower {} > upper {}", link.name, written(lo), written(hi)),
        fmt::format("write joint_range: [{}, {}]", limit(hi * (std::abs(hi) < kUnlimited ? shown : 1)),
                    limit(lo * (std::abs(lo) < kUnlimited ? shown : 1))));
  } else {
    ctx.report(f,
               fmt::format("joint range of link \"{}\" has zero width ({} .. {}): the joint cannot move", link.name,
                           written(lo), written(hi)),
               "use joint_type: fixed for a joint that must not move");
  }
}

void check_axes_and_ranges(const RuleContext& ctx) {
  for (const PhysicalFinding& f : ctx.physical.findings) {
    const Link& link = ctx.model.links[static_cast<std::size_t>(f.link)];
    switch (f.defect) {
      case PhysicalDefect::kAxisZero:
      case PhysicalDefect::kAxisNotUnit: report_axis(ctx, f, link); break;
      case PhysicalDefect::kRangeReversed:
      case PhysicalDefect::kRangeZeroWidth: report_range(ctx, f, link); break;
      default: break;  // the inertia rules' (inertia.cpp)
    }
  }
}

void check_velocity(const RuleContext& ctx, const Link& link) {
  if (!is_one_dof(link) && link.joint_type != JointType::kPseudoContinuousTrack) return;
  const double lo = link.velocity_lower, hi = link.velocity_upper;
  if (lo <= 0 && 0 <= hi) return;
  const SourceLocation at = source_of(link, LinkSources::kJointVelocity);
  const bool revolute = link.joint_type == JointType::kRevolute;
  const double shown = revolute && ctx.model.angles_in_degrees ? 180 / kPi : 1.0;
  const char* unit = revolute ? (ctx.model.angles_in_degrees ? " deg/s" : " rad/s") : " m/s";
  auto written = [&](double v) { return std::abs(v) >= kUnlimited ? limit(v) : num(v * shown) + unit; };
  std::string what = lo > hi ? "a negative velocity limit" : "a velocity range that excludes zero";
  ctx.report("joint-velocity-negative", at,
             fmt::format("link \"{}\" has {} ({} .. {}): the joint cannot stand still within it", link.name, what,
                         written(lo), written(hi)),
             "max_joint_velocity is a positive magnitude; joint_velocity_range must contain 0");
}

}  // namespace

void check_joints(const RuleContext& ctx) {
  check_ids(ctx);
  check_axes_and_ranges(ctx);
  for (const Link& link : ctx.model.links) check_velocity(ctx, link);
}

}  // namespace bodyfmt::validate::detail
