// Device parameter rules (body-format-spec §10): values Choreonoid accepts silently but that
// make a sensor or light useless or break a renderer.

#include "rule_context.h"

#include <fmt/format.h>

#include <vector>

namespace bodyfmt::validate::detail {
namespace {

std::string deg(double radians) { return num(radians * 180 / kPi) + " deg"; }

std::string device_name(const Device& d) {
  return d.name.empty() ? d.type + " device" : d.type + " \"" + d.name + "\"";
}

void check_camera(const RuleContext& ctx, const Device& d, const CameraParams& c) {
  // A perspective (NORMAL) lens needs 0 < fov < 180 degrees; Choreonoid's fisheye lenses
  // render up to a full 360 degrees (TankBody's DUAL_FISHEYE "Theta" uses 180).
  const bool fisheye = c.lens_type == "FISHEYE" || c.lens_type == "DUAL_FISHEYE";
  const bool fov_ok =
      fisheye ? c.field_of_view > 0 && c.field_of_view <= 2 * kPi : c.field_of_view > 0 && c.field_of_view < kPi;
  if (!fov_ok) {
    ctx.report("device-fov", d.key_source({"field_of_view", "fieldOfView"}),
               fmt::format("{} has field_of_view {}, outside {}", device_name(d), deg(c.field_of_view),
                           fisheye ? "(0, 360] degrees for a fisheye lens" : "(0, 180) degrees"),
               "field_of_view is an angle in the file's angle unit (degrees in format 2.0), e.g. 45");
  }
  if (c.width <= 0 || c.height <= 0) {
    ctx.report("device-resolution", c.width <= 0 ? d.key_source({"width"}) : d.key_source({"height"}),
               fmt::format("{} has a non-positive resolution {} x {}", device_name(d), c.width, c.height),
               "width and height are positive pixel counts");
  }
  if (c.near_clip_distance <= 0 || c.near_clip_distance >= c.far_clip_distance) {
    ctx.report("device-clip",
               c.near_clip_distance <= 0 ? d.key_source({"near_clip_distance", "nearClipDistance"})
                                         : d.key_source({"far_clip_distance", "farClipDistance"}),
               fmt::format("{} has near_clip_distance {} and far_clip_distance {}: need 0 < near < far", device_name(d),
                           num(c.near_clip_distance), num(c.far_clip_distance)));
  } else if (d.type == "RangeCamera" && c.min_distance >= c.max_distance) {
    ctx.report("device-clip", d.key_source({"max_distance"}),
               fmt::format("{} has min_distance {} >= max_distance {}", device_name(d), num(c.min_distance),
                           num(c.max_distance)));
  }
}

void check_range_sensor(const RuleContext& ctx, const Device& d, const RangeSensorParams& r) {
  if (r.min_distance >= r.max_distance || r.min_distance < 0) {
    ctx.report("device-clip",
               r.min_distance < 0 ? d.key_source({"min_distance", "minDistance"})
                                  : d.key_source({"max_distance", "maxDistance"}),
               fmt::format("{} has min_distance {} and max_distance {}: need 0 <= min < max", device_name(d),
                           num(r.min_distance), num(r.max_distance)));
  }
  if ((r.yaw_range > 0 && r.yaw_step <= 0) || (r.pitch_range > 0 && r.pitch_step <= 0)) {
    ctx.report("device-resolution",
               r.yaw_range > 0 && r.yaw_step <= 0 ? d.key_source({"yaw_step", "yawStep", "scanStep"})
                                                  : d.key_source({"pitch_step", "pitchStep"}),
               fmt::format("{} has a non-positive scan step (yaw_step {}, pitch_step {})", device_name(d),
                           deg(r.yaw_step), deg(r.pitch_step)));
  }
}

void check_light(const RuleContext& ctx, const Device& d, const LightParams& l) {
  std::vector<std::string> problems;
  const SourceLocation* at = nullptr;  // the value of the first problem
  auto problem = [&](std::initializer_list<std::string_view> key, std::string text) {
    if (!at) at = &d.key_source(key);
    problems.push_back(std::move(text));
  };
  if (l.intensity < 0) problem({"intensity"}, fmt::format("intensity {} < 0", num(l.intensity)));
  if ((l.color.array() < 0).any() || (l.color.array() > 1).any())
    problem({"color"}, fmt::format("color {} outside [0, 1]", vec(l.color)));
  if ((l.attenuation.array() < 0).any())
    problem({"attenuation"}, fmt::format("attenuation {} has a negative term", vec(l.attenuation)));
  else if (l.attenuation.isZero(0))
    problem({"attenuation"}, "attenuation [0, 0, 0] divides by zero");
  if (d.type == "SpotLight") {
    if (!(l.cut_off_angle > 0 && l.cut_off_angle <= kPi))
      problem({"cut_off_angle", "cutOffAngle"},
              fmt::format("cut_off_angle {} outside (0, 180] degrees", deg(l.cut_off_angle)));
    if (!(l.beam_width > 0))
      problem({"beam_width", "beamWidth"}, fmt::format("beam_width {} is not positive", deg(l.beam_width)));
    if (l.cut_off_exponent < 0)
      problem({"cut_off_exponent", "cutOffExponent"}, fmt::format("cut_off_exponent {} < 0", num(l.cut_off_exponent)));
    if (l.direction.norm() < 1e-9) problem({"direction"}, "direction is the zero vector");
  }
  if (problems.empty()) return;
  ctx.report("device-light", *at, fmt::format("{}: {}", device_name(d), fmt::join(problems, "; ")));
}

}  // namespace

void check_devices(const RuleContext& ctx) {
  for (const Device& d : ctx.model.devices) {
    if (const auto* c = std::get_if<CameraParams>(&d.params))
      check_camera(ctx, d, *c);
    else if (const auto* r = std::get_if<RangeSensorParams>(&d.params))
      check_range_sensor(ctx, d, *r);
    else if (const auto* l = std::get_if<LightParams>(&d.params))
      check_light(ctx, d, *l);
  }
}

}  // namespace bodyfmt::validate::detail
