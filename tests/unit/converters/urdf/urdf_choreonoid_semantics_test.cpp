// Two readings of one URDF (issue 44): a wrapper body file around it loads as Choreonoid's URDF
// loader loads it (src/URDFBodyLoader/URDFBodyLoader.cpp in the Choreonoid mirror), urdf2body
// writes the URDF meaning and notes where Choreonoid differs. Expected values are Choreonoid's
// rules as read in its source, worked out by hand for each small URDF here:
//  - a link without <inertial> is left at cnoid::Link's defaults: m = 1, c = 0, I = identity
//    (Link::Link in src/Body/Link.cpp); an <inertial> without <inertia> gets identity, R I Rᵀ = I;
//  - every link is a link: a root named `world` is the body's root (setRootLink), on a free
//    joint (setJointType(FreeJoint)); its child hangs from it on the joint the file gives;
//  - every joint's <axis> is read, a fixed joint's too: normalised, or 1 0 0 without one;
//  - MeshGenerator::generateBox refuses only a negative edge (size < 0): a zero box is a (flat)
//    mesh, a negative one an SgShape without a mesh, i.e. no shape;
//  - toVector3 reads a number, spaces, at most one comma, for each of three numbers.
// Each case also runs urdf2body and reads its .body back, with the Body loader's rules.
#include "model_file_readers.h"
#include "support/load_helpers.h"
#include "support/run_command.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace bodyfmt::test {
namespace {

namespace fs = std::filesystem;

std::string strip(std::string_view urdf) { return std::string(urdf.substr(!urdf.empty() && urdf.front() == '\n')); }

/// `model_file: robot.urdf` beside the URDF, loaded as every tool loads it.
LoadResult load_wrapped(std::string_view urdf) {
  LoadOptions options;
  tools::add_model_file_readers(options);
  options.load_meshes = false;
  options.use_ros_package_path = false;
  options.file_texts["/wrapped/robot.urdf"] = strip(urdf);
  CollectingSink sink;
  LoadResult r;
  r.model = load_body_string("model_file: robot.urdf\n", "/wrapped/robot.body", options, sink);
  r.diagnostics = sink.diagnostics();
  return r;
}

struct Imported {
  CommandResult run;  ///< urdf2body's exit code and messages
  std::string body;   ///< the .body it wrote ("" if none)
  LoadResult loaded;  ///< that .body read back by the Body loader
};

Imported urdf2body(std::string_view urdf, const std::string& name, const std::string& flags = "") {
  const fs::path dir = fs::temp_directory_path() / ("bodyfmt_urdf_semantics_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "robot.urdf") << strip(urdf);
  Imported out;
  out.run =
      run_command(std::string(BODYFMT_URDF2BODY) + " robot.urdf -o robot.body --no-meshes " + flags, dir.string());
  if (fs::exists(dir / "robot.body")) {
    std::ifstream in(dir / "robot.body");
    std::ostringstream text;
    text << in.rdbuf();
    out.body = text.str();
    CollectingSink sink;
    out.loaded.model = load_body((dir / "robot.body").string(), LoadOptions{}, sink);
    out.loaded.diagnostics = sink.diagnostics();
  }
  fs::remove_all(dir);
  return out;
}

bool has_line(const std::string& output, const std::string& location, const std::string& rule) {
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    if (line.find(location) != std::string::npos && line.find("[" + rule + "]") != std::string::npos) return true;
  return false;
}

const char* const kNoInertial = R"(
<robot name="r">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/></inertial>
  </link>
  <link name="tool_frame"/>
  <link name="probe">
    <inertial><origin xyz="0.1 0 0" rpy="0 0 1"/><mass value="0.5"/></inertial>
  </link>
  <joint name="mount" type="fixed">
    <parent link="base"/><child link="tool_frame"/><origin xyz="0 0 0.5"/>
  </joint>
  <joint name="probe_mount" type="fixed">
    <parent link="base"/><child link="probe"/>
  </joint>
</robot>
)";

TEST_CASE("urdf semantics (a): a link without <inertial> is 1 kg with identity inertia in a wrapper") {
  LoadResult r = load_wrapped(kNoInertial);
  const MassProperties tool = compute_mass_properties(r.link("tool_frame"));
  CHECK(tool.mass == 1);
  CHECK(tool.center_of_mass == Eigen::Vector3d::Zero());
  CHECK(tool.inertia == Eigen::Matrix3d::Identity());
  // An <inertial> without <inertia>: its mass and centre, identity inertia (R I Rᵀ = I).
  const MassProperties probe = compute_mass_properties(r.link("probe"));
  CHECK(probe.mass == 0.5);
  CHECK(probe.center_of_mass.isApprox(Eigen::Vector3d(0.1, 0, 0)));
  CHECK(probe.inertia.isApprox(Eigen::Matrix3d::Identity()));
  CHECK(compute_mass_properties(r.link("base")).mass == 2);
  CHECK(pos(r.take("wrapper-urdf-mass")) == Pos{5, 3});  // <link name="tool_frame"/>
  CHECK(pos(r.take("wrapper-urdf-mass")) == Pos{7, 5});  // the <inertial> without <inertia>
  r.expect_clean();
}

TEST_CASE("urdf semantics (a): urdf2body keeps the link massless and notes Choreonoid's 1 kg") {
  Imported out = urdf2body(kNoInertial, "a");
  // The <inertial> without <inertia> is refused as urdfdom refuses it (--best-effort writes it).
  CHECK(out.run.status == 2);
  CHECK(out.body.empty());
  CHECK(has_line(out.run.output, "robot.urdf:7:5: error", "import-structure"));
  out = urdf2body(kNoInertial, "a", "--best-effort");
  REQUIRE_MESSAGE(out.loaded.model, out.run.output);
  CHECK(has_line(out.run.output, "robot.urdf:5:3: note", "import-choreonoid-differs"));
  CHECK(compute_mass_properties(out.loaded.link("tool_frame")).mass == 0);
  CHECK(compute_mass_properties(out.loaded.link("base")).mass == 2);
}

const char* const kWorld = R"(
<robot name="r">
  <link name="world"/>
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/></inertial>
  </link>
  <joint name="anchor" type="fixed">
    <parent link="world"/><child link="base"/><origin xyz="0 0 1"/>
  </joint>
</robot>
)";

TEST_CASE("urdf semantics (b): a root 'world' link stays the free root link in a wrapper") {
  LoadResult r = load_wrapped(kWorld);
  const Model& m = r.m();
  REQUIRE(m.links.size() == 2);
  CHECK(m.links[0].name == "world");
  CHECK(m.links[0].joint_type == JointType::kFree);
  CHECK(compute_mass_properties(m.links[0]).mass == 1);  // no <inertial>: Link's defaults
  CHECK(m.links[1].name == "base");
  CHECK(m.links[1].parent == 0);
  CHECK(m.links[1].joint_type == JointType::kFixed);
  CHECK(m.links[1].joint_name == "anchor");
  CHECK(m.links[1].X_PL.translation() == Eigen::Vector3d(0, 0, 1));
  CHECK(pos(r.take("wrapper-urdf-world")) == Pos{2, 9});  // world's name: the robot is not fixed
  CHECK(pos(r.take("wrapper-urdf-mass")) == Pos{2, 3});   // world has no <inertial>: 1 kg
  r.expect_clean();
}

TEST_CASE("urdf semantics (b): urdf2body makes the world's child the fixed root and notes it") {
  Imported out = urdf2body(kWorld, "b");
  REQUIRE_MESSAGE(out.loaded.model, out.run.output);
  CHECK(out.run.status == 0);
  CHECK(has_line(out.run.output, "robot.urdf:2:9: note", "import-choreonoid-differs"));
  const Model& m = out.loaded.m();
  REQUIRE(m.links.size() == 1);
  CHECK(m.links[0].name == "base");
  CHECK(m.links[0].joint_type == JointType::kFixed);
  CHECK(m.links[0].X_PL.translation() == Eigen::Vector3d(0, 0, 1));
}

const char* const kFixedAxes = R"(
<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="c"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/><axis xyz="0 3 4"/></joint>
  <joint name="ac" type="fixed"><parent link="a"/><child link="c"/></joint>
</robot>
)";

TEST_CASE("urdf semantics (c): a fixed joint keeps the file's axis, normalised, or 1 0 0 in a wrapper") {
  LoadResult r = load_wrapped(kFixedAxes);
  CHECK(r.link("b").joint_type == JointType::kFixed);
  CHECK(r.link("b").joint_axis.isApprox(Eigen::Vector3d(0, 0.6, 0.8)));
  CHECK(r.link("c").joint_axis == Eigen::Vector3d(1, 0, 0));
  r.expect_clean();
}

TEST_CASE("urdf semantics (c): urdf2body writes no axis for a fixed joint (URDF: it has none)") {
  Imported out = urdf2body(kFixedAxes, "c");
  REQUIRE_MESSAGE(out.loaded.model, out.run.output);
  CHECK(out.run.status == 0);
  CHECK(out.body.find("joint_axis") == std::string::npos);
  // Read back, a fixed joint without joint_axis has cnoid::Link's default axis, Z.
  CHECK(out.loaded.link("b").joint_axis == Eigen::Vector3d(0, 0, 1));
}

const char* const kBoxes = R"(
<robot name="r">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><box size="0 0 0"/></geometry></visual>
    <visual><geometry><box size="0.1 0 0.3"/></geometry></visual>
    <collision><geometry><box size="0.1 -0.2 0.3"/></geometry></collision>
    <collision><geometry><sphere radius="-1"/></geometry></collision>
  </link>
</robot>
)";

TEST_CASE("urdf semantics (d): a negative box edge makes no shape, a zero one a flat box, in a wrapper") {
  LoadResult r = load_wrapped(kBoxes);
  const Link& base = r.link("base");
  REQUIRE(base.shapes.size() == 2);  // the two visual boxes; neither collision shape
  for (const Shape& s : base.shapes) {
    CHECK(s.visual);
    CHECK_FALSE(s.collision);
  }
  CHECK(std::get<Box>(base.shapes[0].geometry).size == Eigen::Vector3d(0, 0, 0));
  CHECK(std::get<Box>(base.shapes[1].geometry).size == Eigen::Vector3d(0.1, 0, 0.3));
  // No error: Choreonoid loads the file, without those two shapes.
  CHECK(pos(r.take("wrapper-urdf-semantics")) == Pos{6, 31});
  CHECK(pos(r.take("wrapper-urdf-semantics")) == Pos{7, 34});
  r.expect_clean();
}

TEST_CASE("urdf semantics (d): urdf2body keeps a zero box and refuses a negative size") {
  Imported out = urdf2body(kBoxes, "d");
  CHECK(out.run.status == 2);
  CHECK(out.body.empty());
  CHECK(has_line(out.run.output, "robot.urdf:6:31: error", "import-value"));
  CHECK(has_line(out.run.output, "robot.urdf:7:34: error", "import-value"));
  out = urdf2body(kBoxes, "d", "--best-effort");
  REQUIRE_MESSAGE(out.loaded.model, out.run.output);
  CHECK(out.loaded.link("base").shapes.size() == 2);
}

const char* const kCommas = R"(
<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="ab" type="revolute">
    <parent link="a"/><child link="b"/>
    <origin xyz="0.07, 0, -0.69" rpy="0 ,0, 0,"/>
    <axis xyz="0,1,0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
)";

TEST_CASE("urdf semantics (e): numbers separated by commas read as Choreonoid reads them") {
  LoadResult r = load_wrapped(kCommas);
  CHECK(r.link("b").X_PL.translation() == Eigen::Vector3d(0.07, 0, -0.69));
  CHECK(r.link("b").X_PL.linear() == Eigen::Matrix3d::Identity());
  CHECK(r.link("b").joint_axis == Eigen::Vector3d(0, 1, 0));
  CHECK(pos(r.take("import-convention")) == Pos{6, 13});
  CHECK(pos(r.take("import-convention")) == Pos{6, 34});
  CHECK(pos(r.take("import-convention")) == Pos{7, 11});
  r.expect_clean();

  Imported out = urdf2body(kCommas, "e");
  REQUIRE_MESSAGE(out.loaded.model, out.run.output);
  CHECK(out.run.status == 0);
  CHECK(has_line(out.run.output, "robot.urdf:6:13: warning", "import-convention"));
  CHECK(out.loaded.link("b").X_PL.translation().isApprox(Eigen::Vector3d(0.07, 0, -0.69)));
  CHECK(out.loaded.link("b").joint_axis.isApprox(Eigen::Vector3d(0, 1, 0)));
}

TEST_CASE("urdf semantics (e): what toVector3 refuses stays an error") {
  // A doubled comma, a missing number, a fourth number.
  for (const char* xyz : {"0,,1,2", "0, 1", "0, 1, 2, 3"}) {
    CAPTURE(xyz);
    std::string urdf = kCommas;
    urdf.replace(urdf.find("0.07, 0, -0.69"), std::strlen("0.07, 0, -0.69"), xyz);
    LoadResult r = load_wrapped(urdf);
    CHECK(pos(r.take("import-value")) == Pos{6, 13});
  }
}

// One defect per mutant of a complete URDF, which loads silently: each is reported once, at its
// place, as what Choreonoid's URDF loader refuses or reads its own way (a root `world` link is
// case (b) above).
const char* const kComplete = R"(
<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><box size="1 1 1"/></geometry></visual>
  </link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="ab" type="revolute">
    <parent link="a"/><child link="b"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="2" velocity="3"/>
  </joint>
</robot>
)";

TEST_CASE("urdf semantics: what Choreonoid's URDF loader refuses or changes, one mutant each") {
  load_wrapped(kComplete).expect_clean();
  struct Mutant {
    const char* find;
    const char* replace;
    const char* rule;
    Pos at;
  };
  const Mutant mutants[] = {
      {"<mass value=\"1\"/><inertia", "<mass value=\"0\"/><inertia", "wrapper-urdf-refused", {3, 21}},
      {" effort=\"2\"", "", "wrapper-urdf-refused", {10, 5}},
      {" velocity=\"3\"", "", "wrapper-urdf-refused", {10, 5}},
      {"effort=\"2\"", "effort=\"-2\"", "wrapper-urdf-refused", {10, 33}},
      {" ixy=\"0\"", "", "wrapper-urdf-refused", {3, 32}},
      {"<axis xyz=\"0 0 1\"/>", "<axis/>", "wrapper-urdf-refused", {9, 5}},
      {"<box size=\"1 1 1\"/>", "<box size=\"1 1 1\"/><sphere radius=\"1\"/>", "wrapper-urdf-refused", {4, 42}},
      {"<box size=\"1 1 1\"/>", "<capsule radius=\"1\" length=\"1\"/>", "wrapper-urdf-refused", {4, 23}},
      {"<link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" "
       "izz=\"1\"/></inertial></link>",
       "<link name=\"b\"/>",
       "wrapper-urdf-mass",
       {6, 3}},
      {"<mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>\n    "
       "<visual>",
       "<mass value=\"1\"/></inertial>\n    <visual>",
       "wrapper-urdf-mass",
       {3, 5}},
      {"type=\"revolute\"", "type=\"floating\"", "wrapper-urdf-semantics", {7, 20}},
      {"type=\"revolute\"", "type=\"planar\"", "wrapper-urdf-semantics", {7, 20}},
      {"type=\"revolute\"", "type=\"screw\"", "wrapper-urdf-semantics", {7, 20}},
      {"<box size=\"1 1 1\"/>", "<cylinder radius=\"1\" length=\"0\"/>", "wrapper-urdf-semantics", {4, 44}},
      {"<box size=\"1 1 1\"/>", "<sphere radius=\"-0.5\"/>", "wrapper-urdf-semantics", {4, 31}},
  };
  for (const Mutant& mutant : mutants) {
    CAPTURE(mutant.replace);
    std::string urdf = kComplete;
    const std::size_t at = urdf.find(mutant.find);
    REQUIRE(at != std::string::npos);
    urdf.replace(at, std::strlen(mutant.find), mutant.replace);
    LoadResult r = load_wrapped(urdf);
    REQUIRE(r.model);
    CHECK(pos(r.take(mutant.rule)) == mutant.at);
    r.expect_clean();
    if (std::strstr(mutant.replace, "type=") && r.model) {
      // Choreonoid sets no joint type for these: the link keeps cnoid::Link's, fixed, and no joint id.
      CHECK(r.link("b").joint_type == JointType::kFixed);
      CHECK(r.link("b").joint_id == -1);
    }
    if (std::strstr(mutant.replace, "<cylinder") || std::strstr(mutant.replace, "<sphere radius=\"-"))
      CHECK(r.link("a").shapes.empty());
  }
}

// Choreonoid's URDF loader collects every material (top level, then each visual's, in document
// order) before it reads the links; urdfdom and urdf2body know a material once it is defined.
const char* const kLateMaterial = R"(
<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><sphere radius="1"/></geometry><material name="blue"/></visual>
  </link>
  <link name="b">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <visual><geometry><sphere radius="1"/></geometry><material name="blue"><color rgba="0 0 1 0.75"/></material></visual>
  </link>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
)";

TEST_CASE("urdf semantics: a visual may name a material a later link defines, in a wrapper") {
  LoadResult r = load_wrapped(kLateMaterial);
  const Shape& shape = r.link("a").shapes.at(0);
  REQUIRE(shape.appearance.material);
  CHECK(shape.appearance.material->diffuse_color == Eigen::Vector3d(0, 0, 1));
  CHECK(shape.appearance.material->transparency == 0.25);
  r.expect_clean();

  Imported out = urdf2body(kLateMaterial, "material");
  CHECK(has_line(out.run.output, "robot.urdf:4:64: warning", "import-material"));
}

}  // namespace
}  // namespace bodyfmt::test
