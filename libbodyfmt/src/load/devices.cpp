#include "load/devices.h"

#include <bodyfmt/body_keys.h>

#include "load/scalar.h"
#include "load/values.h"

#include <algorithm>
#include <array>

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

void read_range_sensor(MappingReader& r, Device& d) {
  RangeSensorParams s;
  assign_if(s.yaw_range, opt_angle(r, {"yaw_range", "yawRange", "scanAngle"}));
  auto min_yaw = opt_angle(r, {"min_yaw_angle"});
  auto max_yaw = opt_angle(r, {"max_yaw_angle"});
  if (min_yaw && max_yaw) s.yaw_range = *max_yaw - *min_yaw;
  assign_if(s.yaw_step, opt_angle(r, {"yaw_step", "yawStep", "scanStep"}));
  r.take({"yaw_samples"});
  assign_if(s.pitch_range, opt_angle(r, {"pitch_range", "pitchRange"}));
  auto min_pitch = opt_angle(r, {"min_pitch_angle"});
  auto max_pitch = opt_angle(r, {"max_pitch_angle"});
  if (min_pitch && max_pitch) s.pitch_range = *max_pitch - *min_pitch;
  assign_if(s.pitch_step, opt_angle(r, {"pitch_step", "pitchStep"}));
  r.take({"pitch_samples"});
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
