// Composition: SubBody includes, YAML fragments, URI forms, ContinuousTrack, mesh resolution
// across the corpus (body-format-spec §8.5, §9, §11).

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "support/load_helpers.h"

namespace fs = std::filesystem;
using bodyfmt::test::LoadResult;
using bodyfmt::test::pos;
using bodyfmt::test::Pos;

namespace {

const std::string kData = std::string(BODYFMT_TEST_DATA_DIR) + "/load/composition/";
const std::string kCorpus = std::string(BODYFMT_SHARED_DIR) + "/corpus/choreonoid/";

LoadResult load_file(const std::string& path, bodyfmt::LoadOptions options = {}) {
  bodyfmt::CollectingSink sink;
  LoadResult result;
  result.model = bodyfmt::load_body(path, options, sink);
  result.diagnostics = sink.diagnostics();
  return result;
}

std::string file_name(const std::string& path) { return fs::path(path).filename().string(); }

}  // namespace

TEST_CASE("load: a SubBody that includes itself is reported with the include chain") {
  auto r = load_file(kData + "self.body");
  auto d = r.take("subbody-recursion");
  CHECK(file_name(d.location.file) == "self.body");
  CHECK(pos(d) == Pos{7, 10});
  CHECK(d.message.find("self.body -> self.body") != std::string::npos);
  CHECK(r.m().links.size() == 1);
}

TEST_CASE("load: mutual SubBody recursion stops at the first repeated file") {
  auto r = load_file(kData + "mutual_a.body");
  auto d = r.take("subbody-recursion");
  CHECK(file_name(d.location.file) == "mutual_b.body");
  CHECK(d.message.find("mutual_a.body -> mutual_b.body -> mutual_a.body") != std::string::npos);
  // A includes B; B's include of A is refused, so the model is A + B.
  CHECK(r.m().links.size() == 2);
  CHECK(r.m().links[1].name == "B");
}

TEST_CASE("load: recursion through three files in two folders is detected") {
  auto r = load_file(kData + "deep_a.body");
  auto d = r.take("subbody-recursion");
  CHECK(file_name(d.location.file) == "deep_c.body");
  CHECK(d.message.find("deep_a.body -> deep_b.body -> deep_c.body -> deep_a.body") != std::string::npos);
  CHECK(r.m().links.size() == 3);
}

TEST_CASE("load: joint_id_offset is read whole with a default of 0, as Choreonoid's Mapping::get does") {
  auto r = load_file(kData + "id_offset_forms.body");
  // 10.0 and abc are not whole integers: no offset (gripper ids 0 and 1), each warned at its value.
  CHECK(r.link("F_PALM").joint_id == 0);
  CHECK(r.link("F_FINGER").joint_id == 1);
  CHECK(r.link("A_PALM").joint_id == 0);
  CHECK(r.link("W_PALM").joint_id == 30);  // the camelCase spelling
  CHECK(r.link("W_FINGER").joint_id == 31);
  CHECK(pos(r.take("load-ignored-value")) == Pos{12, 22});
  CHECK(pos(r.take("load-ignored-value")) == Pos{17, 22});
  CHECK_FALSE(r.has("load-number"));
  CHECK_FALSE(r.has("load-lenient-number"));
}

TEST_CASE("load: SubBody prefixes, suffixes, id offsets, device prefix and root overrides") {
  auto r = load_file(kData + "includer.body");
  const bodyfmt::Model& m = r.m();
  // BASE, L_PALM_1, L_FINGER_1, R_PALM, R_FINGER in depth-first order.
  REQUIRE(m.links.size() == 5);
  CHECK(m.links[1].name == "L_PALM_1");
  CHECK(m.links[2].name == "L_FINGER_1");
  CHECK(m.links[3].name == "R_PALM");
  CHECK(m.links[4].name == "R_FINGER");
  CHECK(m.links[2].parent == 1);
  const bodyfmt::Link& left = r.link("L_PALM_1");
  CHECK(left.joint_id == 10);
  CHECK(r.link("L_FINGER_1").joint_id == 11);
  CHECK(r.link("R_PALM").joint_id == 20);
  // The override's translation and rotation (degrees: the includer's unit) replace the root offset.
  CHECK(left.X_PL.translation().isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  CHECK(left.X_PL.linear().isApprox(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
  // Findings about the overridden pose point at the includer; the name stays in the sub-body.
  CHECK(left.sources.translation().file.str() == kData + "includer.body");
  CHECK(left.sources.translation().line == 14);
  CHECK(left.sources.translation().column == 18);
  CHECK(left.sources.rotation().file.str() == kData + "includer.body");
  CHECK(left.sources.rotation().line == 15);
  CHECK(left.sources.name().file.str() == kData + "sub/gripper.body");
  CHECK(left.sources.name().line == 7);
  CHECK(left.sources.mass().file.str() == kData + "sub/gripper.body");
  CHECK(left.sources.mass().line == 14);
  // §11.2: a SubBody node without joint_range resets the range, velocity and rotor inertia.
  CHECK(left.joint_range_upper == bodyfmt::kUnlimited);
  CHECK(left.velocity_upper == bodyfmt::kUnlimited);
  CHECK(left.joint_axis_inertia == 0);
  // ... while the R_ include gives a range, in the includer's degrees.
  const bodyfmt::Link& right = r.link("R_PALM");
  CHECK(right.joint_range_lower == doctest::Approx(-M_PI / 6).epsilon(1e-12));
  CHECK(right.joint_range_upper == doctest::Approx(M_PI / 6).epsilon(1e-12));
  // Non-root links keep the sub-body's own radians.
  CHECK(r.link("R_FINGER").joint_range_upper == doctest::Approx(0.02));
  // Mass keys and RigidBody nodes of the SubBody node are ignored; the added Sphere is kept.
  CHECK(left.mass_contributions.size() == 1);
  CHECK(left.mass_contributions[0].mass == doctest::Approx(0.5));
  CHECK(left.shapes.size() == 2);
  CHECK(r.count("load-mass-ignored") == 2);
  // Devices get the device prefix (default: the prefix) and follow their link.
  REQUIRE(m.devices.size() == 2);
  CHECK(m.devices[0].name == "left_eye");
  CHECK(m.devices[0].link == 1);
  CHECK(m.devices[1].name == "R_eye");
  // Extra joints are carried over with their links renamed.
  REQUIRE(m.extra_joints.size() == 2);
  CHECK(m.links[static_cast<std::size_t>(m.extra_joints[0].link2)].name == "L_FINGER_1");
}

TEST_CASE("load: YAML fragments see the main file's anchors and resolve URIs from their own folder") {
  bodyfmt::LoadOptions options;
  options.package_paths.push_back(kData + "pkgroot");
  auto r = load_file(kData + "fragments.body", options);
  const bodyfmt::Link& cart = r.link("CART");
  // WHEEL: a RigidBody and a Cylinder placed by the Resource node's translation.
  REQUIRE(cart.mass_contributions.size() == 1);
  CHECK(cart.mass_contributions[0].mass == doctest::Approx(1.5));
  CHECK(cart.mass_contributions[0].center_of_mass.isApprox(Eigen::Vector3d(0.2, 0, 0)));
  REQUIRE(cart.shapes.size() == 3);
  CHECK(std::holds_alternative<bodyfmt::Cylinder>(cart.shapes[0].geometry));
  REQUIRE(cart.shapes[0].appearance.material);
  CHECK(cart.shapes[0].appearance.material->diffuse_color.isApprox(Eigen::Vector3d(1, 0, 0)));
  // PLATE: `../pkgroot/...` relative to parts/, and the package:// form, resolve to one file.
  const auto& plate = bodyfmt::geometry_get<bodyfmt::MeshResource>(cart.shapes[1].geometry);
  const auto& package = bodyfmt::geometry_get<bodyfmt::MeshResource>(cart.shapes[2].geometry);
  CHECK(fs::equivalent(plate.resolved_path, kData + "pkgroot/mypkg/meshes/cube.stl"));
  CHECK(plate.resolved_path == package.resolved_path);
  CHECK(plate.mesh >= 0);
  CHECK(plate.mesh == package.mesh);  // one asset for one file
  bodyfmt::CollectingSink sink;
  auto bounds = bodyfmt::compute_link_bounds(r.m(), sink);
  CHECK(bounds[0].visual.max.z() == doctest::Approx(3.0));  // cube.stl is 2 high, moved up by 1
}

TEST_CASE("load: an unknown package is a located error naming the package") {
  auto r = bodyfmt::test::load_v2(R"(
links:
  - name: A
    elements:
      - type: Resource
        uri: package://nowhere/mesh.stl
)");
  auto d = r.take("load-uri");
  CHECK(pos(d) == Pos{7, 14});
  CHECK(d.message.find("nowhere") != std::string::npos);
}

TEST_CASE("load: file:// URIs and a missing mesh file name the resolved path") {
  const std::string cube = fs::canonical(kData + "pkgroot/mypkg/meshes/cube.stl").string();
  auto r = bodyfmt::test::load_v2("\nlinks:\n  - name: A\n    elements:\n      - type: Resource\n        uri: file://" +
                                  cube + "\n      - type: Resource\n        uri: missing/part.stl\n");
  const bodyfmt::Link& a = r.link("A");
  REQUIRE(a.shapes.size() == 2);
  CHECK(bodyfmt::geometry_get<bodyfmt::MeshResource>(a.shapes[0].geometry).mesh >= 0);
  auto d = r.take("mesh-file-missing");
  CHECK(d.message.find("missing/part.stl") != std::string::npos);
  CHECK(d.location.line == 9);  // the uri: value that names it, not the Resource node on line 8
  CHECK(d.location.column == 14);
}

TEST_CASE("load: ContinuousTrack expands into a chain of links") {
  auto r = bodyfmt::test::load_v2(R"(
links:
  - name: BODY
    joint_type: free
  - type: ContinuousTrack
    name: BELT
    parent: BODY
    translation: [0, 0.3, 0]
    joint_axis: Y
    numJoints: 4
    joint_offset: [0.05, 0, 0]
    initialJointAngles: [10, 20]
    mass: 0.2
    elements:
      - type: Shape
        geometry: { type: Box, size: [0.05, 0.1, 0.01] }
)");
  const bodyfmt::Model& m = r.m();
  REQUIRE(m.links.size() == 5);
  CHECK(m.links[1].name == "BELT0");
  CHECK(m.links[1].joint_type == bodyfmt::JointType::kFree);
  CHECK(m.links[1].X_PL.translation().isApprox(Eigen::Vector3d(0, 0.3, 0)));
  for (int i = 2; i <= 4; ++i) {
    const bodyfmt::Link& link = m.links[static_cast<std::size_t>(i)];
    CHECK(link.name == "BELT" + std::to_string(i - 1));
    CHECK(link.parent == i - 1);
    CHECK(link.joint_type == bodyfmt::JointType::kRevolute);
    CHECK(link.X_PL.translation().isApprox(Eigen::Vector3d(0.05, 0, 0)));
    CHECK(link.shapes.size() == 1);
    CHECK(link.mass_contributions.at(0).mass == doctest::Approx(0.2));
  }
  CHECK(m.links[2].initial_displacement == doctest::Approx(M_PI / 18));
  CHECK(m.links[3].initial_displacement == doctest::Approx(M_PI / 9));
  CHECK(m.links[4].initial_displacement == 0);  // missing entries are 0
}

TEST_CASE("load: every ContinuousTrack link keeps the template's rotation (the clone's offset translation only)") {
  auto r = bodyfmt::test::load_v2(R"(
links:
  - name: BODY
    joint_type: free
  - type: ContinuousTrack
    name: BELT
    parent: BODY
    translation: [0, 0.3, 0]
    rotation: [1, 0, 0, 90]
    joint_axis: Y
    numJoints: 3
    joint_offset: [0.05, 0, 0]
)");
  const bodyfmt::Model& m = r.m();
  REQUIRE(m.links.size() == 4);
  const Eigen::Matrix3d rx90 = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  CHECK(m.links[1].X_PL.translation().isApprox(Eigen::Vector3d(0, 0.3, 0)));
  for (int i = 1; i <= 3; ++i) {
    CAPTURE(i);
    CHECK(m.links[static_cast<std::size_t>(i)].X_PL.linear().isApprox(rx90, 1e-15));
  }
  CHECK(m.links[2].X_PL.translation().isApprox(Eigen::Vector3d(0.05, 0, 0)));
  CHECK(m.links[3].X_PL.translation().isApprox(Eigen::Vector3d(0.05, 0, 0)));
}

TEST_CASE("load: a ContinuousTrack with too few joints is an error") {
  auto r = bodyfmt::test::load_v2(R"(
links:
  - name: BODY
  - type: ContinuousTrack
    name: BELT
    parent: BODY
    numJoints: 2
    joint_offset: [0.05, 0, 0]
)");
  CHECK(pos(r.take("load-continuous-track")) == Pos{8, 16});
}

// The issue's mesh-heavy models: every mesh reference must resolve to an imported asset.
TEST_CASE("load: mesh-heavy corpus models resolve every mesh") {
  for (const char* model : {"GR001/GR001.body", "JACO2/JACO2.body", "UniversalRobots/UR5.body", "Robotiq/2F-85.body",
                            "Tank/Tank.body", "PA10/PA10.body", "AizuSpider/AizuSpiderNS.body"}) {
    CAPTURE(model);
    auto r = load_file(kCorpus + model);
    int meshes = 0;
    for (const bodyfmt::Link& link : r.m().links) {
      for (const bodyfmt::Shape& shape : link.shapes) {
        if (const auto* mesh = bodyfmt::geometry_if<bodyfmt::MeshResource>(shape.geometry)) {
          ++meshes;
          CAPTURE(mesh->uri);
          CHECK(mesh->mesh >= 0);
          if (mesh->mesh >= 0) CHECK_FALSE(r.m().meshes[static_cast<std::size_t>(mesh->mesh)].parts.empty());
        }
      }
    }
    CHECK(meshes > 0);
    for (const bodyfmt::Diagnostic& d : r.diagnostics) {
      CAPTURE(bodyfmt::format_diagnostic(d));
      CHECK(d.severity < bodyfmt::Severity::kError);
    }
  }
}

TEST_CASE("load: a YAML fragment that names itself is refused where it does, not followed until the stack ends") {
  auto r = load_file(kData + "yaml_cycle.body");
  auto d = r.take("resource-recursion");
  CHECK(file_name(d.location.file.str()) == "yaml_cycle.yaml");
  CHECK(pos(d) == Pos{3, 50});  // the fragment name PART on the Resource node inside PART
  CHECK(d.message.find("yaml_cycle.yaml#PART -> yaml_cycle.yaml#PART") != std::string::npos);
  r.expect_clean();
  CHECK(r.link("BASE").shapes.size() == 1);  // the sphere, read once
}

TEST_CASE("load: a ContinuousTrack is named as Choreonoid names it, and its links share the joint name and id") {
  auto r = bodyfmt::test::load_v2(R"(
links:
  - name: BODY
    joint_type: free
  - type: ContinuousTrack
    name: BELT
    joint_name: BELT_JOINT
    joint_id: 0
    joint_angle: 15
    parent: BODY
    joint_axis: Y
    numJoints: 3
    joint_offset: [0.05, 0, 0]
    initialJointAngles: [10]
  - name: WHEEL
    parent: BELT
    joint_type: revolute
    joint_axis: Y
    joint_id: 1
)");
  // StdBodyLoader: readLinkContents registers BELT, addTrackLink then BELT0 for the same link,
  // so `parent: BELT` is BELT0. The clones (Link's copy constructor) keep the joint name and
  // id; addTrackLink gives BELT0 the angle 0 and the next ones initialJointAngles.
  const bodyfmt::Model& m = r.m();
  REQUIRE(m.links.size() == 5);
  const bodyfmt::Link& wheel = r.link("WHEEL");
  REQUIRE(wheel.parent >= 0);
  CHECK(m.links[static_cast<std::size_t>(wheel.parent)].name == "BELT0");
  for (const char* name : {"BELT0", "BELT1", "BELT2"}) {
    CAPTURE(name);
    CHECK(r.link(name).joint_name == "BELT_JOINT");
    CHECK(r.link(name).joint_id == 0);
  }
  CHECK(r.link("BELT0").initial_displacement == 0);
  CHECK(r.link("BELT1").initial_displacement == doctest::Approx(M_PI / 18));
  CHECK(r.link("BELT2").initial_displacement == 0);
  CHECK(pos(r.take("load-track-shared-joint")) == Pos{8, 17});  // joint_name
  CHECK(pos(r.take("load-track-shared-joint")) == Pos{9, 15});  // joint_id
  CHECK(pos(r.take("load-ignored-value")) == Pos{10, 18});      // joint_angle reaches no link
  CHECK(pos(r.take("load-track-name")) == Pos{17, 13});         // parent: BELT
  r.expect_clean();

  // The node's name is taken: another link of that name is a duplicate, as in Choreonoid.
  auto dup = bodyfmt::test::load_v2(R"(
links:
  - name: BODY
  - type: ContinuousTrack
    name: BELT
    numJoints: 3
    joint_offset: [0.05, 0, 0]
    parent: BODY
  - name: BELT
    parent: BODY
)");
  CHECK(pos(dup.take("structure-duplicate-link")) == Pos{10, 11});
}
