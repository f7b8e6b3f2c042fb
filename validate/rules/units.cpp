// Unit rules (issue 4, "Units"): numbers that are probably written in the wrong unit.
// units-radian-in-2.0 is the loader's (it alone sees the header), and so are the findings of a
// value in the other unit that carry a fix-it or stop the format upgrade: units-range-looks-degree,
// units-velocity-looks-degree and units-rotation-looks-radian (load/unit_checks.cpp: the loader
// alone sees each file's own unit and the text to edit).

#include "rule_context.h"

#include <bodyfmt/unit_heuristics.h>

#include <fmt/format.h>

#include <algorithm>

#include <cmath>
#include <vector>

namespace bodyfmt::validate::detail {
namespace {

using units::kRadianMatch;

bool near_pi_multiple(double w) { return units::pi_twelfths(w) > 0; }

// body-format-spec §3: in a degree file, a revolute range like [-1.57, 1.57] is ±1.57 degrees.
// Heuristic (documented in the rule table): the finite limits, as written, are all within
// 2π (+0.002) in magnitude, at least one is non-zero, and either
//   (a) some non-zero limit lies within 0.002 of a multiple of π/12 (±3.14, ±1.57, 0.785,
//       2.0944, 6.283...), or
//   (b) every non-zero limit is within π (+0.002) and none is a whole number.
void check_radian_range(const RuleContext& ctx, const Link& link) {
  if (!ctx.model.angles_in_degrees || link.joint_type != JointType::kRevolute) return;
  std::vector<double> written;
  for (double v : {link.joint_range_lower, link.joint_range_upper})
    if (std::abs(v) < kUnlimited) written.push_back(v * 180 / kPi);
  bool any_nonzero = false, all_small = true, all_within_pi = true, all_fractional = true, near_multiple = false;
  for (double w : written) {
    if (std::abs(w) < 1e-12) continue;
    any_nonzero = true;
    if (std::abs(w) > 2 * kPi + kRadianMatch) all_small = false;
    if (std::abs(w) > kPi + kRadianMatch) all_within_pi = false;
    if (std::abs(w - std::round(w)) < 1e-9) all_fractional = false;
    if (near_pi_multiple(w)) near_multiple = true;
  }
  if (!any_nonzero || !all_small || !(near_multiple || (all_within_pi && all_fractional))) return;
  std::vector<std::string> as_written, as_degrees;
  for (double v : {link.joint_range_lower, link.joint_range_upper}) {
    if (std::abs(v) >= kUnlimited) {
      as_written.push_back(limit(v));
      as_degrees.push_back(limit(v));
    } else {
      const double w = v * 180 / kPi;
      as_written.push_back(num(w));
      // 1.57 means π/2: suggest the 90 it stands for, not 89.9544.
      const double k = std::round(std::abs(w) / (kPi / 12));
      const double meant = std::abs(std::abs(w) - k * kPi / 12) <= kRadianMatch ? std::copysign(k * 15, w)
                                                                                : std::round(w * 180 / kPi * 1e4) / 1e4;
      as_degrees.push_back(num(meant));
    }
  }
  ctx.report("units-range-looks-radian", source_of(link, LinkSources::kJointRange),
             fmt::format("joint range [{}] of link \"{}\" is read in degrees but looks like radians (it would be "
                         "[{}] degrees)",
                         fmt::join(as_written, ", "), link.name, fmt::join(as_degrees, ", ")),
             fmt::format("write joint_range: [{}] (format 2.0 angles are degrees)", fmt::join(as_degrees, ", ")));
}

// A prismatic limit beyond 10 m is far more likely millimetres than metres.
constexpr double kPrismaticLimit = 10.0;

void check_prismatic_range(const RuleContext& ctx, const Link& link) {
  if (link.joint_type != JointType::kPrismatic) return;
  double worst = 0;
  for (double v : {link.joint_range_lower, link.joint_range_upper})
    if (std::abs(v) < kUnlimited) worst = std::max(worst, std::abs(v));
  if (worst <= kPrismaticLimit) return;
  ctx.report("units-prismatic-millimetres", source_of(link, LinkSources::kJointRange),
             fmt::format("prismatic joint range [{}, {}] of link \"{}\" reaches {} m, which looks like millimetres",
                         limit(link.joint_range_lower), limit(link.joint_range_upper), link.name, num(worst)),
             fmt::format("prismatic ranges are metres: joint_range: [{}, {}]", limit(link.joint_range_lower / 1000),
                         limit(link.joint_range_upper / 1000)));
}

// A mesh asset in metres (no length_unit) whose box is > 100x the link's other geometry, or
// > 10 m across on a moving link, was probably exported in millimetres.
constexpr double kMeshRatio = 100.0;
constexpr double kMeshSize = 10.0;

void check_mesh_scale(const RuleContext& ctx, LinkIndex index) {
  const Link& link = ctx.model.links[index];
  const auto is_resource = [](const Shape& shape) { return geometry_is<MeshResource>(shape.geometry); };
  if (std::none_of(link.shapes.begin(), link.shapes.end(), is_resource)) return;  // only meshes are measured
  std::vector<double> sizes(link.shapes.size(), 0.0);
  std::vector<bool> is_mesh(link.shapes.size(), false);
  for (std::size_t s = 0; s < link.shapes.size(); ++s) {
    const Shape& shape = link.shapes[s];
    BoundingBox box;
    if (const auto* mesh = geometry_if<MeshResource>(shape.geometry)) {
      if (mesh->mesh < 0 || mesh->length_scale != 1.0) continue;
      const MeshAsset& asset = ctx.model.meshes[mesh->mesh];
      for (const MeshPart& part : asset.parts) box.add(bounding_box(part.mesh, shape.X_LS));
      is_mesh[s] = true;
    } else {
      continue;  // primitives are measured below from their parameters
    }
    if (!box.empty()) sizes[s] = (box.max - box.min).maxCoeff();
  }
  // Other geometry: primitives' sizes come from their own boxes.
  for (std::size_t s = 0; s < link.shapes.size(); ++s) {
    if (!is_mesh[s] || sizes[s] <= 0) continue;
    double other = 0;
    for (std::size_t o = 0; o < link.shapes.size(); ++o) {
      if (o == s) continue;
      const Shape& shape = link.shapes[o];
      double size = sizes[o];
      if (!is_mesh[o]) {
        if (const auto* b = std::get_if<Box>(&shape.geometry))
          size = b->size.maxCoeff();
        else if (const auto* sp = std::get_if<Sphere>(&shape.geometry))
          size = 2 * sp->radius;
        else if (const auto* c = std::get_if<Cylinder>(&shape.geometry))
          size = std::max(2 * c->radius, c->height);
        else if (const auto* k = std::get_if<Cone>(&shape.geometry))
          size = std::max(2 * k->radius, k->height);
        else if (const auto* cap = std::get_if<Capsule>(&shape.geometry))
          size = cap->height + 2 * cap->radius;
        size *= shape.X_LS.linear().colwise().norm().maxCoeff();
      }
      other = std::max(other, size);
    }
    const bool ratio = other > 0 && sizes[s] > kMeshRatio * other;
    const bool huge = sizes[s] > kMeshSize && is_moving(link);
    if (!ratio && !huge) continue;
    const auto& mesh = geometry_get<MeshResource>(link.shapes[s].geometry);
    const std::string why =
        ratio ? fmt::format("{} times the link's other geometry ({} m)", num(sizes[s] / other), num(other))
              : fmt::format("more than {} m across on a moving link", num(kMeshSize));
    ctx.report("units-mesh-millimetres", first_known({link.shapes[s].source, link.source}),
               fmt::format("mesh \"{}\" of link \"{}\" is {} m across, {}: it looks like millimetres", mesh.uri,
                           link.name, num(sizes[s]), why),
               "add metadata: { length_unit: millimeter } to the Resource");
  }
}

}  // namespace

void check_units(const RuleContext& ctx) {
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(ctx.model.links.size()); ++i) {
    check_radian_range(ctx, ctx.model.links[i]);
    check_prismatic_range(ctx, ctx.model.links[i]);
    check_mesh_scale(ctx, i);
  }
}

}  // namespace bodyfmt::validate::detail
