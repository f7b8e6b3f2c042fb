#include "load/devices.h"

#include "load/scalar.h"
#include "load/values.h"

#include <algorithm>
#include <array>

namespace bodyfmt::detail {
namespace {

constexpr std::array<std::string_view, 17> kCoreDevices = {
    "ForceSensor", "RateGyroSensor", "AccelerationSensor", "IMU",        "Camera",
    "CameraDevice", "RangeSensor",   "PointLight",         "SpotLight",  "DigitalIO",
    "Holder",       "Attachment",    "Conveyor",           "ZmpDevice",  "MarkerDevice",
    "VisionSensor", "RangeCamera"};

constexpr std::array<std::string_view, 14> kPluginNodes = {
    "RotorDevice",       "FireDevice",          "SmokeDevice",
    "RainDevice",        "SnowDevice",          "FountainDevice",
    "LivoxMid360",       "CompetitorMarker",    "PxContinuousTrack",
    "AGXVehicleContinuousTrackDevice", "AGXBreakableJointDevice", "AGXMagneticJointDevice",
    "AGXWireDevice",     "StdActionController"};

template <typename T>
void set_if(T& target, const std::optional<T>& value) {
  if (value) target = *value;
}

std::optional<double> opt_double(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  return optional_double(r.context(), ref);
}

std::optional<double> opt_angle(MappingReader& r, KeyNames names) {
  auto v = opt_double(r, names);
  if (!v) return std::nullopt;
  return r.context().angle(*v);
}

std::optional<Eigen::Vector3d> opt_vec3(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  return read_optional_vec3(r.context(), ref);
}

std::string opt_string(MappingReader& r, KeyNames names, std::string fallback) {
  yaml::NodeRef ref = r.take(names);
  if (ref && ref->is_scalar()) return ref->scalar;
  return fallback;
}

bool read_camera(MappingReader& r, Device& d) {
  LoadContext& ctx = r.context();
  CameraParams c;
  yaml::NodeRef format = r.take({"format"});
  c.format = format && format->is_scalar() ? format->scalar : "";
  static const std::array<std::string_view, 5> kFormats = {"COLOR", "DEPTH", "COLOR_DEPTH",
                                                           "POINT_CLOUD", "COLOR_POINT_CLOUD"};
  if (std::find(kFormats.begin(), kFormats.end(), c.format) == kFormats.end()) {
    // body-format-spec §10.2: Choreonoid drops such a camera without a word.
    ctx.warning("device-camera-dropped", format ? format : r.node(),
                c.format.empty() ? "this Camera has no format; Choreonoid silently drops it"
                                 : "unknown camera format \"" + c.format + "\"; Choreonoid silently drops the camera",
                "set format to COLOR, DEPTH, COLOR_DEPTH, POINT_CLOUD or COLOR_POINT_CLOUD");
    return false;
  }
  d.type = c.format == "COLOR" ? "Camera" : "RangeCamera";
  c.lens_type = opt_string(r, {"lens_type", "lensType"}, c.lens_type);
  if (auto w = r.take({"width"})) set_if(c.width, std::optional<int>(optional_int(ctx, w)));
  if (auto h = r.take({"height"})) set_if(c.height, std::optional<int>(optional_int(ctx, h)));
  set_if(c.field_of_view, opt_angle(r, {"field_of_view", "fieldOfView"}));
  set_if(c.near_clip_distance, opt_double(r, {"near_clip_distance", "nearClipDistance"}));
  set_if(c.far_clip_distance, opt_double(r, {"far_clip_distance", "farClipDistance"}));
  set_if(c.frame_rate, opt_double(r, {"frame_rate", "frameRate"}));
  c.optical_frame = opt_string(r, {"optical_frame"}, c.optical_frame);
  if (c.optical_frame != "gl" && c.optical_frame != "cv" && c.optical_frame != "robotics")
    ctx.error("device-optical-frame", r.node()->find("optical_frame")->value,
              "unknown optical frame type \"" + c.optical_frame + "\"", "use gl, cv or robotics");
  set_if(c.min_distance, opt_double(r, {"min_distance"}));
  set_if(c.max_distance, opt_double(r, {"max_distance"}));
  set_if(c.detection_rate, opt_double(r, {"detection_rate"}));
  set_if(c.error_deviation, opt_double(r, {"error_deviation"}));
  r.take({"optical_frame_rotation"});
  d.params = c;
  return true;
}

void read_range_sensor(MappingReader& r, Device& d) {
  RangeSensorParams s;
  set_if(s.yaw_range, opt_angle(r, {"yaw_range", "yawRange", "scanAngle"}));
  auto min_yaw = opt_angle(r, {"min_yaw_angle"});
  auto max_yaw = opt_angle(r, {"max_yaw_angle"});
  if (min_yaw && max_yaw) s.yaw_range = *max_yaw - *min_yaw;
  set_if(s.yaw_step, opt_angle(r, {"yaw_step", "yawStep", "scanStep"}));
  r.take({"yaw_samples"});
  set_if(s.pitch_range, opt_angle(r, {"pitch_range", "pitchRange"}));
  auto min_pitch = opt_angle(r, {"min_pitch_angle"});
  auto max_pitch = opt_angle(r, {"max_pitch_angle"});
  if (min_pitch && max_pitch) s.pitch_range = *max_pitch - *min_pitch;
  set_if(s.pitch_step, opt_angle(r, {"pitch_step", "pitchStep"}));
  r.take({"pitch_samples"});
  set_if(s.min_distance, opt_double(r, {"min_distance", "minDistance"}));
  set_if(s.max_distance, opt_double(r, {"max_distance", "maxDistance"}));
  set_if(s.scan_rate, opt_double(r, {"scan_rate", "scanRate"}));
  set_if(s.scan_rate, opt_double(r, {"frame_rate"}));
  set_if(s.detection_rate, opt_double(r, {"detection_rate"}));
  set_if(s.error_deviation, opt_double(r, {"error_deviation"}));
  r.take({"optical_frame"});
  r.take({"optical_frame_rotation"});
  d.type = "RangeSensor";
  d.params = s;
}

void read_light(MappingReader& r, Device& d, bool spot) {
  LightParams l;
  set_if(l.color, opt_vec3(r, {"color"}));
  set_if(l.intensity, opt_double(r, {"intensity"}));
  set_if(l.attenuation, opt_vec3(r, {"attenuation"}));
  if (spot) {
    set_if(l.direction, opt_vec3(r, {"direction"}));
    set_if(l.beam_width, opt_angle(r, {"beam_width", "beamWidth"}));
    set_if(l.cut_off_angle, opt_angle(r, {"cut_off_angle", "cutOffAngle"}));
    set_if(l.cut_off_exponent, opt_double(r, {"cut_off_exponent", "cutOffExponent"}));
  }
  d.type = spot ? "SpotLight" : "PointLight";
  d.params = l;
}

}  // namespace

bool is_core_device_type(std::string_view type) {
  return std::find(kCoreDevices.begin(), kCoreDevices.end(), type) != kCoreDevices.end();
}

bool is_plugin_node_type(std::string_view type) {
  return std::find(kPluginNodes.begin(), kPluginNodes.end(), type) != kPluginNodes.end();
}

bool read_device_params(MappingReader& r, std::string_view t, Device& d) {
  if (t == "Camera" || t == "CameraDevice" || t == "VisionSensor" || t == "RangeCamera") return read_camera(r, d);
  if (t == "RangeSensor") {
    read_range_sensor(r, d);
  } else if (t == "SpotLight" || t == "PointLight") {
    read_light(r, d, t == "SpotLight");
  } else if (t == "ForceSensor") {
    ForceSensorParams f;
    set_if(f.max_force, opt_vec3(r, {"max_force", "maxForce"}));
    set_if(f.max_torque, opt_vec3(r, {"max_torque", "maxTorque"}));
    d.type = "ForceSensor";
    d.params = f;
  } else if (t == "RateGyroSensor" || t == "AccelerationSensor" || t == "IMU") {
    InertialSensorParams s;
    if (t == "IMU") {
      set_if(s.max_angular_velocity, opt_vec3(r, {"max_angular_velocity"}));
      set_if(s.max_acceleration, opt_vec3(r, {"max_acceleration"}));
    } else if (t == "RateGyroSensor") {
      set_if(s.max_angular_velocity, opt_vec3(r, {"max_angular_velocity", "maxAngularVelocity"}));
    } else {
      set_if(s.max_acceleration, opt_vec3(r, {"max_acceleration", "maxAcceleration"}));
    }
    d.type = t == "IMU" ? "Imu" : std::string(t);
    d.params = s;
  } else {
    // Devices no stage interprets yet keep their scalar keys only.
    static const std::pair<std::string_view, std::string_view> kClassNames[] = {
        {"DigitalIO", "DigitalIoDevice"}, {"Holder", "HolderDevice"},
        {"Attachment", "AttachmentDevice"}, {"Conveyor", "ConveyorDevice"}};
    d.type = std::string(t);
    for (const auto& [node, cls] : kClassNames)
      if (node == t) d.type = std::string(cls);
    for (const yaml::MapEntry& e : r.node()->entries) r.ignore(e.key);
  }
  return true;
}

}  // namespace bodyfmt::detail
