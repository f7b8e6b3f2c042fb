#include "load/devices.h"

#include <bodyfmt/body_keys.h>

#include "load/scalar.h"
#include "load/values.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace bodyfmt::detail {
namespace {

constexpr std::array<std::string_view, 14> kPluginNodes = {"RotorDevice",
                                                           "FireDevice",
                                                           "SmokeDevice",
                                                           "RainDevice",
                                                           "SnowDevice",
                                                           "FountainDevice",
                                                           "LivoxMid360",
                                                           "CompetitorMarker",
                                                           "PxContinuousTrack",
                                                           "AGXVehicleContinuousTrackDevice",
                                                           "AGXBreakableJointDevice",
                                                           "AGXMagneticJointDevice",
                                                           "AGXWireDevice",
                                                           "StdActionController"};

std::optional<double> opt_angle(MappingReader& r, KeyNames names) { return take_optional_angle(r, names); }

std::optional<Eigen::Vector3d> opt_vec3(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  return read_optional_vec3(r.context(), ref);
}

std::string opt_string(MappingReader& r, KeyNames names, std::string fallback) {
  yaml::NodeRef ref = r.take(names);
  if (ref && ref->is_scalar()) return std::string(ref->scalar());
  return fallback;
}

bool read_camera(MappingReader& r, Device& d) {
  LoadContext& ctx = r.context();
  CameraParams c;
  yaml::NodeRef format = r.take({"format"});
  c.format = format && format->is_scalar() ? format->scalar() : "";
  static const std::array<std::string_view, 5> kFormats = {"COLOR", "DEPTH", "COLOR_DEPTH", "POINT_CLOUD",
                                                           "COLOR_POINT_CLOUD"};
  if (std::find(kFormats.begin(), kFormats.end(), c.format) == kFormats.end()) {
    // body-format-spec §10.2: Choreonoid drops such a camera without a word.
    ctx.report("device-camera-dropped", format ? format : r.node(),
               c.format.empty() ? "this Camera has no format; Choreonoid silently drops it"
                                : "unknown camera format \"" + c.format + "\"; Choreonoid silently drops the camera",
               "set format to COLOR, DEPTH, COLOR_DEPTH, POINT_CLOUD or COLOR_POINT_CLOUD");
    return false;
  }
  d.type = c.format == "COLOR" ? "Camera" : "RangeCamera";
  if (yaml::NodeRef lens = r.take({"lens_type", "lensType"}); lens && lens->is_scalar()) {
    // Camera::readSpecifications sets only the three lens types it knows: any other word
    // leaves the constructor's NORMAL lens, without a word.
    const std::string_view t = lens->scalar();
    if (t == "NORMAL" || t == "FISHEYE" || t == "DUAL_FISHEYE")
      c.lens_type = std::string(t);
    else
      ctx.report("load-ignored-value", lens,
                 "unknown lens type \"" + std::string(t) + "\"; Choreonoid keeps the NORMAL lens",
                 "use NORMAL, FISHEYE or DUAL_FISHEYE");
  }
  if (auto w = r.take({"width"})) assign_if(c.width, std::optional<int>(optional_int(ctx, w)));
  if (auto h = r.take({"height"})) assign_if(c.height, std::optional<int>(optional_int(ctx, h)));
  assign_if(c.field_of_view, opt_angle(r, {"field_of_view", "fieldOfView"}));
  assign_if(c.near_clip_distance, take_optional_double(r, {"near_clip_distance", "nearClipDistance"}));
  assign_if(c.far_clip_distance, take_optional_double(r, {"far_clip_distance", "farClipDistance"}));
  assign_if(c.frame_rate, take_optional_double(r, {"frame_rate", "frameRate"}));
  c.optical_frame = opt_string(r, {"optical_frame"}, c.optical_frame);
  if (c.optical_frame != "gl" && c.optical_frame != "cv" && c.optical_frame != "robotics")
    ctx.report("device-optical-frame", r.node()->find("optical_frame")->value,
               "unknown optical frame type \"" + c.optical_frame + "\"", "use gl, cv or robotics");
  assign_if(c.min_distance, take_optional_double(r, {"min_distance"}));
  assign_if(c.max_distance, take_optional_double(r, {"max_distance"}));
  assign_if(c.detection_rate, take_optional_double(r, {"detection_rate"}));
  assign_if(c.error_deviation, take_optional_double(r, {"error_deviation"}));
  // readAngleAxis skips a value that is not a list, and an empty list, without a word.
  if (auto rot = r.take({"optical_frame_rotation"})) {
    if (listing_or_ignored(ctx, rot, "optical_frame_rotation")) {
      if (rot->items().empty())
        ctx.report("load-ignored-value", rot, "optical_frame_rotation is an empty list; Choreonoid skips it",
                   "write [x, y, z, angle]");
      else if (auto R = read_rotation(ctx, rot))
        c.optical_frame_rotation = *R;
    }
  }
  d.params = c;
  return true;
}

// One scan axis of a RangeSensor as Choreonoid's RangeSensor reads it: min and max angles
// before a range (a range of |v| centred on 0), max below min ignored; a step (a negative one
// ignored) before a number of samples n, which makes the step range / (n - 1), or 0 for one
// sample (n below 1 ignored). The model keeps the width and the step: an asymmetric min/max
// keeps its width only.
struct ScanAxisKeys {
  KeyNames min, max, range, step;
  std::string_view samples;
};

void read_scan_axis(MappingReader& r, const ScanAxisKeys& keys, double& range, double& step) {
  LoadContext& ctx = r.context();
  auto angle = [&](KeyNames names) -> std::pair<yaml::NodeRef, std::optional<double>> {
    yaml::NodeRef ref = r.take(names);
    std::optional<double> v = ref ? optional_double(ctx, ref) : std::nullopt;
    return {ref, v ? std::optional<double>(ctx.angle(*v, ref)) : std::nullopt};
  };
  auto ignored = [&](const yaml::NodeRef& at, const std::string& why) {
    ctx.report("load-ignored-value", at, why + "; Choreonoid ignores it and keeps the default");
  };
  auto [min_ref, lo] = angle(keys.min);
  auto [max_ref, hi] = angle(keys.max);
  auto [range_ref, width] = angle(keys.range);
  if (lo && hi) {
    if (*hi >= *lo)
      range = *hi - *lo;
    else
      ignored(max_ref, "the maximum angle is below the minimum");
  } else if (width) {
    range = std::abs(*width);
  }
  auto [step_ref, by] = angle(keys.step);
  yaml::NodeRef samples_ref = r.take({keys.samples});
  if (step_ref) {
    if (by && *by >= 0)
      step = *by;
    else if (by)
      ignored(step_ref, "a negative step");
  } else if (samples_ref) {
    if (auto n = optional_int(ctx, samples_ref)) {
      if (*n >= 1)
        step = *n == 1 ? 0.0 : range / static_cast<double>(*n - 1);
      else
        ignored(samples_ref, "fewer than one sample");
    }
  }
}

void read_range_sensor(MappingReader& r, Device& d) {
  RangeSensorParams s;
  s.pitch_step = 0;  // Choreonoid's constructor: no pitch range, and no pitch step
  read_scan_axis(r,
                 {{"min_yaw_angle"},
                  {"max_yaw_angle"},
                  {"yaw_range", "yawRange", "scanAngle"},
                  {"yaw_step", "yawStep", "scanStep"},
                  "yaw_samples"},
                 s.yaw_range, s.yaw_step);
  read_scan_axis(r,
                 {{"min_pitch_angle"},
                  {"max_pitch_angle"},
                  {"pitch_range", "pitchRange"},
                  {"pitch_step", "pitchStep"},
                  "pitch_samples"},
                 s.pitch_range, s.pitch_step);
  assign_if(s.min_distance, take_optional_double(r, {"min_distance", "minDistance"}));
  assign_if(s.max_distance, take_optional_double(r, {"max_distance", "maxDistance"}));
  // VisionSensor::readSpecifications reads frame_rate first, RangeSensor's own reader then
  // scan_rate, which wins when both are written.
  assign_if(s.scan_rate, take_optional_double(r, {"frame_rate", "frameRate"}));
  assign_if(s.scan_rate, take_optional_double(r, {"scan_rate", "scanRate"}));
  assign_if(s.detection_rate, take_optional_double(r, {"detection_rate"}));
  assign_if(s.error_deviation, take_optional_double(r, {"error_deviation"}));
  // The same check as a camera's: Choreonoid refuses an unknown optical frame for every
  // VisionSensor ("Unknown optical frame type").
  if (yaml::NodeRef frame = r.take({"optical_frame"})) {
    if (!frame->is_scalar() || (frame->scalar() != "gl" && frame->scalar() != "cv" && frame->scalar() != "robotics"))
      r.context().report("device-optical-frame", frame,
                         "unknown optical frame type" +
                             (frame->is_scalar() ? " \"" + std::string(frame->scalar()) + "\"" : std::string()),
                         "use gl, cv or robotics");
  }
  r.context().note_rotation_angles(r.take({"optical_frame_rotation"}));
  d.type = "RangeSensor";
  d.params = s;
}

void read_light(MappingReader& r, Device& d, bool spot) {
  LightParams l;
  assign_if(l.color, opt_vec3(r, {"color"}));
  assign_if(l.intensity, take_optional_double(r, {"intensity"}));
  assign_if(l.attenuation, opt_vec3(r, {"attenuation"}));
  if (spot) {
    assign_if(l.direction, opt_vec3(r, {"direction"}));
    assign_if(l.beam_width, opt_angle(r, {"beam_width", "beamWidth"}));
    assign_if(l.cut_off_angle, opt_angle(r, {"cut_off_angle", "cutOffAngle"}));
    assign_if(l.cut_off_exponent, take_optional_double(r, {"cut_off_exponent", "cutOffExponent"}));
  }
  d.type = spot ? "SpotLight" : "PointLight";
  d.params = l;
}

}  // namespace

void note_first_angle(MappingReader& r, KeyNames names, bool rotation) {
  // Choreonoid reads the first spelling present (§14); the model does not keep the value.
  for (std::string_view name : names) {
    if (const yaml::MapEntry* entry = r.node()->find(name)) {
      const yaml::NodeRef value = r.node().child(entry->value);
      if (rotation)
        r.context().note_rotation_angles(value);
      else
        r.context().note_angle(value);
      return;
    }
  }
}

namespace {

/// A vector key read with EigenArchive's read(): skipped when it is no list, refused when the
/// list has another size.
void check_vector_key(MappingReader& r, std::string_view key, int size) {
  const yaml::MapEntry* e = r.node()->find(key);
  if (!e) return;
  const yaml::NodeRef value = r.node().child(e->value);
  if (listing_or_ignored(r.context(), value, key)) read_vector(r.context(), value, size);
}

// The checks of the devices bodyfmt keeps as key lists, where their Choreonoid readers
// refuse the file. The keys themselves are kept by the caller.

void check_marker(MappingReader& r) {
  // MarkerDevice::readSpecifications: read({marker_type, markerType}) takes the first
  // spelling that is a scalar; a type other than these three is "Unknown marker type".
  for (std::string_view key : {"marker_type", "markerType"}) {
    const yaml::MapEntry* e = r.node()->find(key);
    if (!e || !e->value->is_scalar()) continue;
    const std::string_view t = e->value->scalar();
    if (t != "cross" && t != "sphere" && t != "axes")
      r.context().report("device-marker-type", r.node().child(e->value),
                         "unknown marker type \"" + std::string(t) + "\"", "use cross, sphere or axes");
    break;
  }
  check_vector_key(r, "color", 3);
  for (std::string_view key : {"offset_translation", "offsetTranslation"}) check_vector_key(r, key, 3);
}

void check_digital_io(MappingReader& r) {
  // DigitalIoDevice::readInputToDeviceSwitchConnections: each item must be a list
  // (toListing throws) of an input number (toInt) and a device name (toString).
  LoadContext& ctx = r.context();
  const yaml::MapEntry* e = r.node()->find("input_to_device_switch_connections");
  if (!e) return;
  const yaml::NodeRef list = r.node().child(e->value);
  if (!listing_or_ignored(ctx, list, "input_to_device_switch_connections")) return;
  for (const yaml::NodeRef& item : list->items()) {
    const yaml::NodeRef pair = list.child(item);
    if (!pair->is_sequence()) {
      ctx.report("load-type", pair, "a connection must be a list [input number, device name]");
    } else if (pair->items().size() != 2) {
      ctx.report("load-vector-size", pair, "the element is not the pair of the input number and the target name");
    } else {
      required_int(ctx, pair.child(pair->items()[0]));
      required_string(ctx, pair.child(pair->items()[1]));
    }
  }
}

}  // namespace

bool is_core_device_type(std::string_view type) {
  const std::vector<std::string_view>& devices = device_type_names();
  return std::find(devices.begin(), devices.end(), type) != devices.end();
}

bool is_plugin_node_type(std::string_view type) {
  return std::find(kPluginNodes.begin(), kPluginNodes.end(), type) != kPluginNodes.end();
}

bool read_device_params(MappingReader& r, std::string_view t, Device& d) {
  if (t == "Camera" || t == "CameraDevice") return read_camera(r, d);
  if (t == "RangeSensor") {
    read_range_sensor(r, d);
  } else if (t == "SpotLight" || t == "PointLight") {
    read_light(r, d, t == "SpotLight");
  } else if (t == "ForceSensor") {
    ForceSensorParams f;
    assign_if(f.max_force, opt_vec3(r, {"max_force", "maxForce"}));
    assign_if(f.max_torque, opt_vec3(r, {"max_torque", "maxTorque"}));
    d.type = "ForceSensor";
    d.params = f;
  } else if (t == "RateGyroSensor" || t == "AccelerationSensor" || t == "IMU") {
    InertialSensorParams s;
    if (t == "IMU") {
      assign_if(s.max_angular_velocity, opt_vec3(r, {"max_angular_velocity"}));
      assign_if(s.max_acceleration, opt_vec3(r, {"max_acceleration"}));
    } else if (t == "RateGyroSensor") {
      assign_if(s.max_angular_velocity, opt_vec3(r, {"max_angular_velocity", "maxAngularVelocity"}));
    } else {
      assign_if(s.max_acceleration, opt_vec3(r, {"max_acceleration", "maxAcceleration"}));
    }
    d.type = t == "IMU" ? "Imu" : std::string(t);
    d.params = s;
  } else {
    // Devices no stage interprets yet keep their scalar keys only.
    static const std::pair<std::string_view, std::string_view> kClassNames[] = {{"DigitalIO", "DigitalIoDevice"},
                                                                                {"Holder", "HolderDevice"},
                                                                                {"Attachment", "AttachmentDevice"},
                                                                                {"Conveyor", "ConveyorDevice"}};
    d.type = std::string(t);
    for (const auto& [node, cls] : kClassNames)
      if (node == t) d.type = std::string(cls);
    if (t == "MarkerDevice") {
      note_first_angle(r, {"offset_rotation", "offsetRotation"}, true);
      check_marker(r);
    } else if (t == "Conveyor") {
      check_vector_key(r, "axis", 3);  // ConveyorDevice::readSpecifications
    } else if (t == "DigitalIO") {
      check_digital_io(r);
    }
    for (const yaml::MapEntry& e : r.node()->entries()) r.ignore(e.key);
  }
  return true;
}

}  // namespace bodyfmt::detail
