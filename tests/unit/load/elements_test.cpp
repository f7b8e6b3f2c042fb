// Loader unit tests for load/elements.cpp: the three forms of `elements`, node types,
// Visual/Collision, Skip, plugin nodes and the transform stack (body-format-spec §7, §8).
// Lines 1-2 are the header written by load_v2; "links:" is line 3.

#include "support/load_helpers.h"

#include <bodyfmt/fix.h>

#include <cmath>

using bodyfmt::Box;
using bodyfmt::Sphere;
using bodyfmt::test::load_v2;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

namespace {
bool near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double eps = 1e-12) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a - b).cwiseAbs().maxCoeff() <= eps;
}
}  // namespace

TEST_CASE("load: elements as a sequence keeps file order") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Sphere, radius: 2}
      - type: Shape
        geometry: {type: Box, size: [1, 2, 3]}
)");
  const auto& shapes = r.link("A").shapes;
  REQUIRE(shapes.size() == 2);
  CHECK(std::get<Sphere>(shapes[0].geometry).radius == 2);
  CHECK(std::get<Box>(shapes[1].geometry).size == Eigen::Vector3d(1, 2, 3));
  r.expect_clean();
}

TEST_CASE("load: elements as a single mapping with type is one node") {
  auto r = load_v2(R"(
links:
  - name: A
    elements: {type: Shape, geometry: {type: Sphere, radius: 3}}
)");
  const auto& shapes = r.link("A").shapes;
  REQUIRE(shapes.size() == 1);
  CHECK(std::get<Sphere>(shapes[0].geometry).radius == 3);
  r.expect_clean();
}

TEST_CASE("load: type-keyed elements mapping is visited in alphabetical key order") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      Shape:
        geometry: {type: Box}
      RigidBody:
        mass: 2
      Collision:
        shape:
          geometry: {type: Sphere, radius: 0.5}
)");
  // Collision < RigidBody < Shape: the collision sphere comes first despite file order.
  const auto& link = r.link("A");
  REQUIRE(link.shapes.size() == 2);
  CHECK(std::get<Sphere>(link.shapes[0].geometry).radius == 0.5);
  CHECK_FALSE(link.shapes[0].visual);
  CHECK(link.shapes[0].collision);
  CHECK(std::get<Box>(link.shapes[1].geometry).size == Eigen::Vector3d(1, 1, 1));
  REQUIRE(link.mass_contributions.size() == 1);
  CHECK(link.mass_contributions[0].mass == 2);
  r.expect_clean();
}

TEST_CASE("load: type-keyed element with a different inner type is load-type-mismatch") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      Shape:
        type: RigidBody
)");
  auto d = r.take("load-type-mismatch");
  CHECK(d.severity == bodyfmt::Severity::kError);
  CHECK(pos(d) == Pos{7, 15});
  r.expect_clean();
}

TEST_CASE("load: scalar elements and a list item without type are errors") {
  auto r = load_v2(R"(
links:
  - name: A
    elements: 3
  - name: B
    parent: A
    elements:
      - geometry: {type: Box}
)");
  CHECK(pos(r.take("load-type")) == Pos{5, 15});
  CHECK(pos(r.take("load-missing-key")) == Pos{9, 9});
  r.expect_clean();
}

TEST_CASE("load: shapes outside Visual/Collision are both, inside only one") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Box}
      - type: Visual
        elements:
          - type: Visual
            shape: {geometry: {type: Sphere, radius: 1}}
      - type: Collision
        elements:
          - type: Transform
            elements:
              - type: Shape
                geometry: {type: Sphere, radius: 2}
)");
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 3);
  CHECK(s[0].visual);
  CHECK(s[0].collision);
  CHECK(s[1].visual);  // Visual inside Visual is fine
  CHECK_FALSE(s[1].collision);
  CHECK_FALSE(s[2].visual);
  CHECK(s[2].collision);
  r.expect_clean();
}

TEST_CASE("load: Visual inside Collision is load-visual-collision-conflict") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Collision
        elements:
          - type: Group
            elements:
              - type: Visual
                shape: {geometry: {type: Box}}
)");
  auto d = r.take("load-visual-collision-conflict");
  CHECK(d.severity == bodyfmt::Severity::kError);
  CHECK(pos(d) == Pos{10, 17});
  CHECK(r.link("A").shapes.empty());
  r.expect_clean();
}

TEST_CASE("load: Skip ignores its whole subtree") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Skip
        elements:
          - type: Shpe
          - type: RigidBody
            mass: 10
)");
  CHECK(r.link("A").shapes.empty());
  CHECK(r.link("A").mass_contributions.empty());
  r.take("load-default-mass");  // the skipped RigidBody leaves the link without mass data
  CHECK(r.diagnostics.empty());
}

TEST_CASE("load: unknown element node type is an error with did-you-mean") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shpe
        geometry: {type: Box}
)");
  auto d = r.take("load-unknown-node-type");
  CHECK(d.severity == bodyfmt::Severity::kError);
  CHECK(pos(d) == Pos{6, 15});
  CHECK(d.fix_hint.find("Shape") != std::string::npos);
  CHECK(r.link("A").shapes.empty());
  r.expect_clean();
}

TEST_CASE("load: unknown node type marked is_optional is only a warning") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: StdFancyController
        is_optional: true
      - type: OtherThing
        isOptional: yes
)");
  auto d = r.take("load-optional-node-skipped");
  CHECK(d.severity == bodyfmt::Severity::kWarning);
  CHECK(pos(d) == Pos{6, 15});
  auto d2 = r.take("load-optional-node-skipped");
  CHECK(d2.severity == bodyfmt::Severity::kWarning);
  CHECK(pos(d2) == Pos{8, 15});
  CHECK(pos(r.take("load-legacy-key")) == Pos{9, 9});  // isOptional
  CHECK(r.m().devices.empty());
  r.expect_clean();
}

TEST_CASE("load: plugin node types are opaque devices with one load-plugin-node warning") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: FireDevice
        name: fire1
        translation: [0, 0, 1]
        life_time: 3
      - type: FireDevice
        name: fire2
)");
  auto d = r.take("load-plugin-node");
  CHECK(d.severity == bodyfmt::Severity::kWarning);
  CHECK(pos(d) == Pos{6, 9});
  CHECK_FALSE(r.has("load-plugin-node"));
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 2);
  CHECK(devices[0].plugin);
  CHECK(devices[0].type == "FireDevice");
  CHECK(devices[0].name == "fire1");
  CHECK(devices[0].keys.at("life_time") == "3");
  CHECK(devices[0].X_LD.translation() == Eigen::Vector3d(0, 0, 1));
  CHECK(devices[1].plugin);
  CHECK(devices[1].name == "fire2");
  r.expect_clean();
}

TEST_CASE("load: device frame is the accumulated Transform stack") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Transform
        translation: [1, 0, 0]
        rotation: [0, 0, 1, 90]
        elements:
          - type: ForceSensor
            name: fs
            translation: [0, 1, 0]
            rotation: [0, 0, 1, 90]
)");
  // X_LD = T(1,0,0) Rz(90) T(0,1,0) Rz(90): p = (1,0,0) + Rz(90) (0,1,0) = (0,0,0);
  // R = Rz(180).
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 1);
  CHECK(near(devices[0].X_LD.translation(), Eigen::Vector3d(0, 0, 0)));
  Eigen::Matrix3d Rz180;
  Rz180 << -1, 0, 0, 0, -1, 0, 0, 0, 1;
  CHECK(near(devices[0].X_LD.linear(), Rz180));
  CHECK(devices[0].type == "ForceSensor");
  CHECK(devices[0].link == 0);
  r.expect_clean();
}

TEST_CASE("load: shape transform X_LS composes translation, rotation and scale") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Transform
        translation: [1, 2, 3]
        scale: [2, 2, 2]
        elements:
          - type: Shape
            translation: [1, 0, 0]
            rotation: [0, 0, 1, 90]
            scale: [1, 3, 1]
            geometry: {type: Box}
)");
  // X_LS = T(1,2,3) S(2) T(1,0,0) Rz(90) S(1,3,1).
  // (1,0,0) -> S -> (1,0,0) -> Rz -> (0,1,0) -> +(1,0,0) -> (1,1,0) -> *2 -> (2,2,0) -> (3,4,3).
  // (0,1,0) -> (0,3,0) -> (-3,0,0) -> (-2,0,0) -> (-4,0,0) -> (-3,2,3).
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 1);
  CHECK(near(s[0].X_LS * Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(3, 4, 3)));
  CHECK(near(s[0].X_LS * Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(-3, 2, 3)));
  CHECK(near(s[0].X_LS * Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 2, 3)));
  r.expect_clean();
}

TEST_CASE("load: a scalar scale is ignored with load-ignored-value") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Transform
        scale: 2
        elements:
          - type: Shape
            geometry: {type: Box}
)");
  CHECK(pos(r.take("load-ignored-value")) == Pos{7, 16});
  CHECK(r.link("A").shapes.at(0).X_LS.matrix().isIdentity());
  r.expect_clean();
}

TEST_CASE("load: translation on a Group is ignored with load-ignored-key") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Group
        translation: [1, 0, 0]
        elements:
          - type: Shape
            geometry: {type: Box}
)");
  CHECK(pos(r.take("load-ignored-key")) == Pos{7, 22});
  CHECK(r.link("A").shapes.at(0).X_LS.translation() == Eigen::Vector3d::Zero());
  r.expect_clean();
}

TEST_CASE("load: a Node is an empty scene node: nothing under it is read, and its elements are warned") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Node
        name: holder
        translation: [0, 0, 1]
        elements:
          - type: RigidBody
            mass: 5
          - type: Shape
            geometry: { type: Sphere, radius: 0.1 }
)");
  // Choreonoid's StdSceneReader makes `new SgNode` of it: no RigidBody (the link keeps its
  // default 1 kg of link-level mass data), no shape.
  const bodyfmt::Link& a = r.link("A");
  CHECK(a.shapes.empty());
  for (const auto& c : a.mass_contributions) CHECK(c.mass != 5);
  CHECK(pos(r.take("load-ignored-key")) == Pos{9, 9});  // elements; a marker's translation loses nothing
  r.expect_clean();
}

TEST_CASE("load: keys Choreonoid reads with findMapping or findListing skip a value of another type, with a warning") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: 5
      - type: Shape
        geometry: { type: Box, size: [1, 2, 3] }
        appearance:
          material:
          texture: abc
      - type: Visual
        resource: x
        shape: []
      - type: RigidBody
        mass: 2
        center_of_mass: 0.5
        inertia: [1, 0, 0, 1, 0, 1]
      - type: Shape
        geometry: { type: Extrusion, cross_section: [0, 0, 1, 0, 1, 1, 0, 0], spine: [0, 0, 0, 0, 1, 0], scale: 1 }
      - type: Camera
        name: cam
        format: COLOR
        optical_frame_rotation: []
)");
  // Choreonoid: StdSceneReader::readShape / readAppearance /
  // readExtrusion, StdBodyLoader::readVisualOrCollision / readRigidBody use findMapping / findListing, which
  // return an invalid node for a value of another type; VisionSensor's readAngleAxis skips
  // an empty list. Nothing is refused.
  // An empty value (material:) is located at its key.
  for (Pos at :
       {Pos{7, 19}, Pos{11, 11}, Pos{12, 20}, Pos{14, 19}, Pos{15, 16}, Pos{18, 25}, Pos{21, 113}, Pos{25, 33}}) {
    CAPTURE(at);
    CHECK(pos(r.take("load-ignored-value")) == at);
  }
  const bodyfmt::Link& a = r.link("A");
  // The Shape without geometry makes nothing; the box keeps the default appearance.
  REQUIRE(a.shapes.size() >= 1);
  CHECK(std::holds_alternative<Box>(a.shapes[0].geometry));
  // The RigidBody's centre of mass stays at its origin.
  REQUIRE(a.mass_contributions.size() == 1);
  CHECK(a.mass_contributions[0].mass == 2);
  CHECK(a.mass_contributions[0].center_of_mass.isZero());
  CHECK_FALSE(r.has("load-type"));
  r.expect_clean();
}

TEST_CASE("load: a device under a scaled Transform keeps its pure rotation, with a warning") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Transform
        scale: [2, 1, 1]
        rotation: [0, 0, 1, 90]
        elements:
          - {type: ForceSensor, name: fs}
      - type: Transform
        rotation: [0, 0, 1, 90]
        elements:
          - {type: RateGyroSensor, name: gyro}
)");
  // StdBodyLoader::readDevice sets the device rotation to the transform stack's linear part,
  // scale included: Rz(90) * diag(2, 1, 1) there. bodyfmt keeps Rz(90) and says so.
  const Eigen::Matrix3d rz90 = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const auto& devices = r.m().devices;
  REQUIRE(devices.size() == 2);
  CHECK(devices[0].X_LD.linear().isApprox(rz90, 1e-15));
  CHECK(devices[1].X_LD.linear().isApprox(rz90, 1e-15));
  CHECK(pos(r.take("device-scaled-frame")) == Pos{10, 13});
  r.expect_clean();
}

// Issue 47: `appearance` one level too deep was a note (load-info-key) and the material was
// lost without a word. It is a warning naming where it belongs, with the edit that moves it up.
TEST_CASE("load: appearance under geometry is load-misplaced-key, and its fix-it moves it to the Shape") {
  const std::string text =
      "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: A\n    elements:\n      Shape:\n"
      "        geometry:\n          type: Box\n          size: [ 1, 2, 3 ]\n          appearance:\n"
      "            material:\n              # green\n              diffuse: [ 0, 0.6, 0 ]\n\n"
      "    mass: 1\n";
  auto r = bodyfmt::test::load(text);
  REQUIRE(r.link("A").shapes.size() == 1);
  CHECK_FALSE(r.link("A").shapes[0].appearance.material.has_value());  // Choreonoid ignores it there
  auto d = r.take("load-misplaced-key");
  CHECK(d.severity == bodyfmt::Severity::kWarning);
  CHECK(pos(d) == Pos{10, 11});
  CHECK(d.message.find("Shape node") != std::string::npos);
  REQUIRE(d.fixes.size() == 1);
  CHECK(d.fixes[0].safety == bodyfmt::FixSafety::kUnsafe);
  r.expect_clean();  // and no load-info-key note for the same key
  CHECK_FALSE(r.has("load-info-key"));
  std::string why;
  const std::optional<std::string> fixed = bodyfmt::apply_fixes(text, d.fixes, why);
  REQUIRE(fixed);
  CHECK(*fixed ==
        "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: A\n    elements:\n      Shape:\n"
        "        geometry:\n          type: Box\n          size: [ 1, 2, 3 ]\n        appearance:\n"
        "          material:\n            # green\n            diffuse: [ 0, 0.6, 0 ]\n\n"
        "    mass: 1\n");
  auto again = bodyfmt::test::load(*fixed);
  REQUIRE(again.link("A").shapes.size() == 1);
  REQUIRE(again.link("A").shapes[0].appearance.material.has_value());
  CHECK(again.link("A").shapes[0].appearance.material->diffuse_color == Eigen::Vector3d(0, 0.6, 0));
  again.expect_clean();
}

TEST_CASE("load: misplaced appearance has no fix-it when it is not geometry's last key or the Shape has one") {
  auto middle = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry:
          type: Box
          appearance: { material: { diffuse: [1, 0, 0] } }
          size: [1, 1, 1]
)");
  auto d = middle.take("load-misplaced-key");
  CHECK(pos(d) == Pos{9, 11});
  CHECK(d.fixes.empty());  // moving it up would carry size out of the geometry
  middle.expect_clean();
  auto both = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        appearance: { material: { diffuse: [0, 0, 1] } }
        geometry:
          type: Box
          appearance: { material: { diffuse: [1, 0, 0] } }
)");
  auto b = both.take("load-misplaced-key");
  CHECK(b.fixes.empty());  // a second appearance key in the Shape
  CHECK(b.fix_hint.find("line 7") != std::string::npos);
  both.expect_clean();
  auto flow = load_v2(R"(
links:
  - name: A
    elements: { Shape: { geometry: { type: Box, appearance: { material: { diffuse: [1, 0, 0] } } } } }
)");
  CHECK(flow.take("load-misplaced-key").fixes.empty());
  flow.expect_clean();
}
