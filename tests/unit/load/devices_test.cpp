// Loader unit tests for load/devices.cpp (body-format-spec §10, §16). load_v2 writes lines
// 1-2; "links:" is line 3, "  - name: A" line 4, "    elements:" line 5.

#include "support/load_helpers.h"

#include <bodyfmt/angles.h>

#include <cmath>

using namespace bodyfmt;
using bodyfmt::test::load;
using bodyfmt::test::load_v2;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

namespace {
using bodyfmt::kPi;
constexpr double kDeg = kPi / 180;

bool near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double eps = 1e-12) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a - b).cwiseAbs().maxCoeff() <= eps;
}
}  // namespace

TEST_CASE("load: a Camera without format is dropped with device-camera-dropped") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Camera
        name: cam
        width: 320
      - type: Camera
        name: cam2
        format: RGB
)");
  auto d = r.take("device-camera-dropped");
  CHECK(d.severity == Severity::kWarning);
  CHECK(pos(d) == Pos{6, 9});  // the node: there is no format key to point at
  auto d2 = r.take("device-camera-dropped");
  CHECK(pos(d2) == Pos{11, 17});  // the bad format value
  CHECK(r.m().devices.empty());
  r.expect_clean();
}

TEST_CASE("load: Camera formats select Camera or RangeCamera, field_of_view in degrees") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Camera
        name: color
        format: COLOR
        lens_type: DUAL_FISHEYE
        field_of_view: 180
        width: 720
        height: 480
        on: false
      - type: Camera
        name: depth
        id: 1
        format: COLOR_DEPTH
        fieldOfView: 65
        width: 320
        height: 240
        frame_rate: 15
        detection_rate: 0.9
        error_deviation: 0.005
)");
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 2);
  CHECK(devices[0].type == "Camera");
  CHECK(devices[0].node_type == "Camera");
  CHECK_FALSE(devices[0].on);
  const auto& c = std::get<CameraParams>(devices[0].params);
  CHECK(c.format == "COLOR");
  CHECK(c.lens_type == "DUAL_FISHEYE");
  CHECK(c.field_of_view == doctest::Approx(kPi).epsilon(1e-15));
  CHECK(c.width == 720);
  CHECK(c.height == 480);
  CHECK(c.near_clip_distance == 0.04);  // defaults
  CHECK(c.far_clip_distance == 200);
  CHECK(c.frame_rate == 30);
  CHECK(devices[1].type == "RangeCamera");
  CHECK(devices[1].id == 1);
  CHECK(devices[1].on);
  const auto& rc = std::get<CameraParams>(devices[1].params);
  CHECK(rc.field_of_view == doctest::Approx(65 * kDeg).epsilon(1e-15));
  CHECK(rc.width == 320);
  CHECK(rc.height == 240);
  CHECK(rc.frame_rate == 15);
  CHECK(rc.detection_rate == 0.9);
  CHECK(rc.error_deviation == 0.005);
  CHECK(rc.min_distance == 0.1);
  CHECK(rc.max_distance == 10);
  CHECK(pos(r.take("load-legacy-key")) == Pos{18, 9});  // fieldOfView
  r.expect_clean();
}

TEST_CASE("load: SpotLight angles in degrees, vectors as written") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: SpotLight
        name: Light
        translation: [0.08, 0, 0.1]
        direction: [1, 0, 0]
        beam_width: 36
        cut_off_angle: 40
        cut_off_exponent: 6
        attenuation: [1, 0, 0.01]
      - type: PointLight
        intensity: 0.5
        color: [1, 0.5, 0]
)");
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 2);
  CHECK(devices[0].type == "SpotLight");
  CHECK(devices[0].name == "Light");
  CHECK(devices[0].X_LD.translation() == Eigen::Vector3d(0.08, 0, 0.1));
  const auto& l = std::get<LightParams>(devices[0].params);
  CHECK(l.direction == Eigen::Vector3d(1, 0, 0));
  CHECK(l.beam_width == doctest::Approx(0.6283185307179586).epsilon(1e-15));  // 36 deg
  CHECK(l.cut_off_angle == doctest::Approx(40 * kDeg).epsilon(1e-15));
  CHECK(l.cut_off_exponent == 6);
  CHECK(l.attenuation == Eigen::Vector3d(1, 0, 0.01));
  CHECK(devices[1].type == "PointLight");
  const auto& p = std::get<LightParams>(devices[1].params);
  CHECK(p.intensity == 0.5);
  CHECK(p.color == Eigen::Vector3d(1, 0.5, 0));
  CHECK(p.attenuation == Eigen::Vector3d(1, 0, 0));
  r.expect_clean();
}

TEST_CASE("load: IMU is device type Imu, the manual's Imu node type is an error") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: IMU
        name: imu
        max_angular_velocity: [1, 2, 3]
      - type: Imu
        name: imu2
      - type: RateGyroSensor
        maxAngularVelocity: [4, 5, 6]
)");
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 2);
  CHECK(devices[0].type == "Imu");
  CHECK(devices[0].node_type == "IMU");
  // max_angular_velocity is read raw (rad/s), never angle-converted.
  CHECK(std::get<InertialSensorParams>(devices[0].params).max_angular_velocity == Eigen::Vector3d(1, 2, 3));
  CHECK(std::get<InertialSensorParams>(devices[0].params).max_acceleration.x() == kUnlimited);
  CHECK(devices[1].type == "RateGyroSensor");
  CHECK(std::get<InertialSensorParams>(devices[1].params).max_angular_velocity == Eigen::Vector3d(4, 5, 6));
  auto d = r.take("load-unknown-node-type");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{9, 15});
  CHECK(d.fix_hint.find("IMU") != std::string::npos);
  CHECK(pos(r.take("load-legacy-key")) == Pos{12, 9});  // maxAngularVelocity
  r.expect_clean();
}

TEST_CASE("load: ForceSensor limits and opaque devices") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: ForceSensor
        max_force: [10, 20, 30]
      - type: Holder
        category: gripper
)");
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 2);
  const auto& f = std::get<ForceSensorParams>(devices[0].params);
  CHECK(f.max_force == Eigen::Vector3d(10, 20, 30));
  CHECK(f.max_torque.x() == kUnlimited);
  CHECK(devices[1].type == "HolderDevice");
  CHECK_FALSE(devices[1].plugin);
  CHECK(devices[1].keys.at("category") == "gripper");
  r.expect_clean();
}

TEST_CASE("load: devices are ordered by link order") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: C
    parent: B
    elements: {type: ForceSensor, name: on_c}
  - name: B
    parent: A
    elements: {type: ForceSensor, name: on_b}
)");
  // Link order A, B, C (depth-first), so B's device comes first.
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 2);
  CHECK(devices[0].name == "on_b");
  CHECK(devices[0].link == 1);
  CHECK(devices[1].name == "on_c");
  CHECK(devices[1].link == 2);
  r.expect_clean();
}

TEST_CASE("load: SimpleTank devices match the reference numbers") {
  CollectingSink sink;
  auto model =
      load_body(std::string(BODYFMT_SHARED_DIR) + "/corpus/choreonoid/Tank/SimpleTank.body", LoadOptions{}, sink);
  REQUIRE(model.has_value());
  CHECK(sink.error_count() == 0);
  REQUIRE(model->devices.size() == 2);
  const Device& light = model->devices[0];
  CHECK(light.type == "SpotLight");
  CHECK(light.link == model->find_link("TURRET_P"));
  const auto& l = std::get<LightParams>(light.params);
  // SimpleTank.ref.yaml: beam_width 0.628318548203, cut_off_angle 0.698131680489, printed
  // from Choreonoid's float members (36 deg = 0.62831853071796 in double): relative 1e-7.
  CHECK(l.beam_width == doctest::Approx(0.628318548203).epsilon(1e-7));
  CHECK(l.cut_off_angle == doctest::Approx(0.698131680489).epsilon(1e-7));
  CHECK(l.beam_width == doctest::Approx(36 * kDeg).epsilon(1e-15));
  const Device& camera = model->devices[1];
  CHECK(camera.name == "Camera");
  CHECK(camera.type == "RangeCamera");
  CHECK(near(camera.X_LD.translation(), Eigen::Vector3d(0.1, 0, 0.05)));
  // SimpleTank.ref.yaml rotation, row-major, = Rx(90) * Ry(-90).
  Eigen::Matrix3d ref;
  ref << 6.12323399574e-17, 0, -1, -1, 6.12323399574e-17, -6.12323399574e-17, 6.12323399574e-17, 1, 3.74939945665e-33;
  CHECK(near(camera.X_LD.linear(), ref, 1e-11));
  const auto& c = std::get<CameraParams>(camera.params);
  CHECK(c.field_of_view == doctest::Approx(1.1344640138).epsilon(1e-9));
  CHECK(c.width == 320);
  CHECK(c.height == 240);
}

TEST_CASE("load: a RangeSensor reads frame_rate, then scan_rate, and refuses an unknown optical frame") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: RangeSensor
        name: both
        frame_rate: 5
        scan_rate: 20
      - type: RangeSensor
        name: camel
        frameRate: 20
      - type: RangeSensor
        name: bad
        optical_frame: ros
)");
  // VisionSensor::readSpecifications reads {frame_rate, frameRate}; RangeSensor's reader then
  // reads {scan_rate, scanRate}, which wins. Both are "Unknown optical frame type" checks.
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 3);
  CHECK(std::get<RangeSensorParams>(devices[0].params).scan_rate == 20);
  CHECK(std::get<RangeSensorParams>(devices[1].params).scan_rate == 20);
  CHECK(pos(r.take("device-optical-frame")) == Pos{15, 24});
  r.take("load-legacy-key");  // frameRate
  r.expect_clean();
}

TEST_CASE("load: RangeCamera and VisionSensor are no node types Choreonoid reads") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - {type: RangeCamera, name: depth, format: DEPTH}
      - {type: VisionSensor, name: vision, format: COLOR, is_optional: true}
      - {type: CameraDevice, name: cam, format: COLOR}
)");
  // Only Camera and CameraDevice register a reader (Camera.cpp); RangeCamera registers a writer
  // under the name Camera, VisionSensor nothing: an unknown node type, skipped if optional.
  CHECK(pos(r.take("load-unknown-node-type")) == Pos{6, 16});
  CHECK(pos(r.take("load-optional-node-skipped")) == Pos{7, 16});
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 1);
  CHECK(devices[0].name == "cam");
  r.expect_clean();
}

TEST_CASE(
    "load: a RangeSensor's scan axes follow RangeSensor.cpp: samples make the step, invalid values keep defaults") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - {type: RangeSensor, name: samples, yaw_range: 180, yaw_samples: 181, pitch_range: 30, pitch_samples: 1}
      - {type: RangeSensor, name: minmax, min_yaw_angle: -30, max_yaw_angle: 90, yaw_step: 0.5}
      - {type: RangeSensor, name: bad, min_yaw_angle: 10, max_yaw_angle: -10, yaw_step: -1, pitch_samples: 0}
      - {type: RangeSensor, name: negative, yaw_range: -90}
      - {type: RangeSensor, name: defaults}
)");
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 5);
  auto params = [&](std::size_t i) { return std::get<RangeSensorParams>(devices[i].params); };
  // setNumYawSamples(181) over 180 deg: pi / 180 per sample; one pitch sample: step 0.
  CHECK(params(0).yaw_range == doctest::Approx(kPi).epsilon(1e-15));
  CHECK(params(0).yaw_step == doctest::Approx(kPi / 180).epsilon(1e-15));
  CHECK(params(0).pitch_range == doctest::Approx(kPi / 6).epsilon(1e-15));
  CHECK(params(0).pitch_step == 0);
  // min/max: the width 120 deg; the step as written.
  CHECK(params(1).yaw_range == doctest::Approx(2 * kPi / 3).epsilon(1e-15));
  CHECK(params(1).yaw_step == doctest::Approx(kPi / 360).epsilon(1e-15));
  // max below min, a negative step and no sample: Choreonoid's defaults (120 deg, 1 rad, pitch 0 and 0).
  CHECK(params(2).yaw_range == doctest::Approx(2 * kPi / 3).epsilon(1e-15));
  CHECK(params(2).yaw_step == 1.0);
  CHECK(params(2).pitch_step == 0);
  // setYawRange(angle) takes |angle|.
  CHECK(params(3).yaw_range == doctest::Approx(kPi / 2).epsilon(1e-15));
  CHECK(params(4).pitch_range == 0);
  CHECK(params(4).pitch_step == 0);
  CHECK(pos(r.take("load-ignored-value")) == Pos{8, 74});
  CHECK(pos(r.take("load-ignored-value")) == Pos{8, 89});
  CHECK(pos(r.take("load-ignored-value")) == Pos{8, 108});
  r.expect_clean();
}

TEST_CASE("load: MarkerDevice, Conveyor and DigitalIO values Choreonoid refuses, and an unknown lens type") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - {type: MarkerDevice, name: m1, marker_type: cube, color: [1, 0], offset_translation: [0, 0, 0]}
      - {type: MarkerDevice, name: m2, markerType: axes, offsetTranslation: [1, 2], color: red}
      - {type: Conveyor, name: c, axis: [1, 0]}
      - {type: DigitalIO, name: io, input_to_device_switch_connections: [[0, m1], [1], lamp, [x, m2]]}
      - {type: Camera, name: cam, format: COLOR, lens_type: PANORAMA}
      - {type: Camera, name: fish, format: COLOR, lens_type: FISHEYE}
)");
  // MarkerDevice::readSpecifications: "Unknown marker type", and read() of a vector refuses a
  // list of another size (a scalar is skipped). ConveyorDevice reads axis the same way.
  // DigitalIoDevice: each connection is toListing()'d, must be a pair, toInt() its first item.
  CHECK(pos(r.take("device-marker-type")) == Pos{6, 53});
  CHECK(pos(r.take("load-vector-size")) == Pos{6, 66});    // color
  CHECK(pos(r.take("load-vector-size")) == Pos{7, 77});    // offsetTranslation
  CHECK(pos(r.take("load-ignored-value")) == Pos{7, 92});  // color: red
  CHECK(pos(r.take("load-vector-size")) == Pos{8, 41});    // Conveyor axis
  CHECK(pos(r.take("load-vector-size")) == Pos{9, 83});    // [1]
  CHECK(pos(r.take("load-type")) == Pos{9, 88});           // lamp
  CHECK(pos(r.take("load-number")) == Pos{9, 95});         // x
  // Camera::readSpecifications keeps the NORMAL lens for a type it does not know.
  CHECK(pos(r.take("load-ignored-value")) == Pos{10, 61});
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 6);
  CHECK(std::get<CameraParams>(devices[4].params).lens_type == "NORMAL");
  CHECK(std::get<CameraParams>(devices[5].params).lens_type == "FISHEYE");
  r.expect_clean();
}
