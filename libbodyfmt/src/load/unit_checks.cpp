#include "load/unit_checks.h"

#include <bodyfmt/readable_number.h>
#include <bodyfmt/unit_heuristics.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace bodyfmt::detail {
namespace {

std::string limit_text(double v) {
  if (std::abs(v) >= kUnlimited) return v < 0 ? "-unlimited" : "unlimited";
  return readable_number(v);
}

// Rounded for the hint: the number a person would write.
std::string as_radians(double degrees) { return readable_number(std::round(degrees * kPi / 180 * 1e4) / 1e4); }

/// The number nodes of a range or limit value: a scalar (both ends) or a pair.
std::vector<yaml::NodeRef> numbers_of(const yaml::NodeRef& value) {
  if (value->is_scalar()) return {value};
  std::vector<yaml::NodeRef> out;
  if (value->is_sequence())
    for (const yaml::NodeRef& item : value->items()) out.push_back(value.child(item));
  return out;
}

/// "Reinterpret as degrees": each finite number replaced by the radians it stands for, in the
/// shortest text that reads back as that double (so a later upgrade writes the degrees again).
std::vector<FixIt> reinterpret_as_degrees(const yaml::NodeRef& value) {
  std::vector<FixIt> fixes;
  for (const yaml::NodeRef& number : numbers_of(value)) {
    if (!number->is_scalar()) return {};
    const char* text = number->scalar().data();  // NUL-terminated
    char* end = nullptr;
    const double written = std::strtod(text, &end);
    if (end == text || !std::isfinite(written) || std::abs(written) >= kUnlimited) continue;  // `unlimited`
    auto fix = edit_value(*number, number_text(written * kPi / 180), FixSafety::kUnsafe);
    if (!fix) return {};  // not written in place: no partial edit
    fixes.push_back(std::move(*fix));
  }
  return fixes;
}

double largest_finite(double lower, double upper) {
  return std::max(std::abs(lower) < kUnlimited ? std::abs(lower) : 0,
                  std::abs(upper) < kUnlimited ? std::abs(upper) : 0);
}

}  // namespace

void check_degree_range(LoadContext& ctx, const Link& link, const yaml::NodeRef& range, double lower, double upper) {
  if (ctx.degrees || link.joint_type != JointType::kRevolute || !units::range_looks_like_degrees(lower, upper)) return;
  const auto radians = [](double v) { return std::abs(v) >= kUnlimited ? limit_text(v) : as_radians(v); };
  ctx.report("units-range-looks-degree", range,
             fmt::format("joint range [{}, {}] of link \"{}\" is read in radians (angle_unit: radian) but looks like "
                         "degrees: it allows {} turns each way",
                         limit_text(lower), limit_text(upper), link.name,
                         readable_number(std::round(largest_finite(lower, upper) / (2 * kPi) * 10) / 10)),
             fmt::format("if these are degrees, the fix-it writes them in radians, [{}, {}]; or angle_unit: degree "
                         "if all the file's angles are degrees",
                         radians(lower), radians(upper)),
             reinterpret_as_degrees(range));
}

void check_degree_velocity(LoadContext& ctx, const Link& link, const yaml::NodeRef& limit, double lower, double upper) {
  if (ctx.degrees || link.joint_type != JointType::kRevolute || !units::velocity_looks_like_degrees(lower, upper))
    return;
  const double fastest = largest_finite(lower, upper);
  ctx.report(
      "units-velocity-looks-degree", limit,
      fmt::format("joint velocity limit {} of link \"{}\" is read in rad/s (angle_unit: radian) but looks like "
                  "deg/s: it allows {} turns a second",
                  readable_number(fastest), link.name, readable_number(std::round(fastest / (2 * kPi) * 10) / 10)),
      fmt::format("{} deg/s is {} rad/s: the fix-it writes that if it is deg/s", readable_number(fastest),
                  as_radians(fastest)),
      reinterpret_as_degrees(limit));
}

void check_radian_rotation(LoadContext& ctx, const yaml::NodeRef& angle, double written) {
  if (!ctx.degrees || !units::rotation_looks_like_radians(written)) return;
  // 1.5708 means π/2: the 90 it stands for, not 1.5708 degrees.
  const double meant = std::copysign(units::pi_twelfths(written) * 15.0, written);
  std::vector<FixIt> fixes;
  if (auto fix = edit_value(*angle, number_text(meant), FixSafety::kUnsafe)) fixes.push_back(std::move(*fix));
  ctx.report("units-rotation-looks-radian", angle,
             fmt::format("rotation angle {} is read in degrees but looks like radians (it would be {} degrees)",
                         readable_number(written), readable_number(meant)),
             fmt::format("write {} (format 2.0 angles and angle_unit: degree are degrees)", readable_number(meant)),
             std::move(fixes));
}

}  // namespace bodyfmt::detail
