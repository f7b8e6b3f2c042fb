// The URDF importer's mapping and its located diagnostics. Expected values are worked out by
// hand from the URDF text (URDF's conventions: rpy = Rz Ry Rx, cylinder along Z, axis in the
// joint frame), not taken from the importer.
#include "urdf_reader.h"

#include "support/load_helpers.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/derived.h>

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace bodyfmt::test {
namespace {

namespace fs = std::filesystem;
using urdf_import::import_urdf;
using urdf_import::UrdfImportOptions;

LoadResult import_text(std::string_view text, const std::string& file = "robot.urdf", UrdfImportOptions options = {}) {
  if (!text.empty() && text.front() == '\n') text.remove_prefix(1);
  CollectingSink sink;
  options.use_ros_package_path = false;
  LoadResult r;
  r.model = import_urdf(text, file, options, sink);
  r.diagnostics = sink.diagnostics();
  return r;
}

const char* const kArm = R"(
<robot name="arm">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="base">
    <inertial>
      <origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/>
      <mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/>
    </inertial>
    <visual><origin xyz="0 0 0.5"/><geometry><cylinder radius="0.1" length="1"/></geometry><material name="red"/></visual>
    <collision><geometry><box size="1 2 3"/></geometry></collision>
  </link>
  <link name="upper">
    <visual><geometry><sphere radius="0.25"/></geometry>
      <material name="half"><color rgba="0 0 1 0.5"/></material></visual>
  </link>
  <link name="tool"/>
  <link name="slider"/>
  <joint name="slide" type="prismatic">
    <parent link="base"/><child link="slider"/>
    <axis xyz="0 0 2"/>
    <limit lower="-0.5" upper="0.25" effort="30" velocity="0.5"/>
  </joint>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/>
    <origin xyz="0 0 1" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="2" effort="10" velocity="3"/>
  </joint>
  <joint name="tool_mount" type="fixed">
    <parent link="upper"/><child link="tool"/>
    <origin xyz="0 0 0.5" rpy="1.5707963267948966 0 0"/>
  </joint>
</robot>
)";

TEST_CASE("urdf import: links, joints, limits and joint ids") {
  LoadResult r = import_text(kArm);
  r.expect_clean();
  const Model& m = r.m();
  REQUIRE(m.links.size() == 4);
  CHECK(m.name == "arm");
  // Depth-first from the root, children in the document order of their joints.
  CHECK(m.links[0].name == "base");
  CHECK(m.links[1].name == "slider");
  CHECK(m.links[2].name == "upper");
  CHECK(m.links[3].name == "tool");
  CHECK(m.links[0].joint_type == JointType::kFree);

  const Link& slider = r.link("slider");
  CHECK(slider.joint_type == JointType::kPrismatic);
  CHECK(slider.joint_id == 0);                                  // first movable joint in the document
  CHECK(slider.joint_axis.isApprox(Eigen::Vector3d(0, 0, 1)));  // normalised
  CHECK(slider.joint_range_lower == -0.5);
  CHECK(slider.joint_range_upper == 0.25);
  CHECK(slider.velocity_upper == 0.5);
  CHECK(slider.effort_upper == 30);
  CHECK(slider.joint_name == "slide");

  const Link& upper = r.link("upper");
  CHECK(upper.joint_type == JointType::kRevolute);
  CHECK(upper.joint_id == 1);
  CHECK(upper.joint_range_lower == -1);
  CHECK(upper.joint_range_upper == 2);
  CHECK(upper.velocity_lower == -3);
  CHECK(upper.X_PL.translation() == Eigen::Vector3d(0, 0, 1));

  // The fixed joint keeps its link and frame.
  const Link& tool = r.link("tool");
  CHECK(tool.joint_type == JointType::kFixed);
  CHECK(tool.joint_id == -1);
  CHECK(tool.X_PL.translation() == Eigen::Vector3d(0, 0, 0.5));
  CHECK((tool.X_PL.linear() * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ(), 1e-15));
  // A link without <inertial> has no mass in URDF.
  CHECK(compute_mass_properties(tool).mass == 0);
}

TEST_CASE("urdf import: the inertial rpy rotates the tensor into the link frame") {
  LoadResult r = import_text(kArm);
  const MassProperties mp = compute_mass_properties(r.link("base"));
  CHECK(mp.mass == 2);
  CHECK(mp.center_of_mass == Eigen::Vector3d(0.1, 0, 0));
  // Yaw 90°: the inertial frame's x is the link's y, so Ixx' = Iyy = 2 and Iyy' = Ixx = 1.
  Eigen::Matrix3d expected = Eigen::Vector3d(2, 1, 3).asDiagonal();
  CHECK((mp.inertia - expected).norm() < 1e-15);
}

TEST_CASE("urdf import: shapes, the cylinder axis and materials") {
  LoadResult r = import_text(kArm);
  const Link& base = r.link("base");
  REQUIRE(base.shapes.size() == 2);
  const Shape& cyl = base.shapes[0];
  CHECK(cyl.visual);
  CHECK_FALSE(cyl.collision);
  REQUIRE(geometry_is<Cylinder>(cyl.geometry));
  CHECK(geometry_get<Cylinder>(cyl.geometry).height == 1);
  // Body's cylinder axis (+Y) must land on URDF's (+Z).
  CHECK(cyl.X_LS.linear() * Eigen::Vector3d::UnitY() == Eigen::Vector3d::UnitZ());
  CHECK(cyl.X_LS.translation() == Eigen::Vector3d(0, 0, 0.5));
  REQUIRE(cyl.appearance.material);
  CHECK(cyl.appearance.material->diffuse_color == Eigen::Vector3d(1, 0, 0));
  const Shape& box = base.shapes[1];
  CHECK_FALSE(box.visual);
  CHECK(box.collision);
  CHECK(geometry_get<Box>(box.geometry).size == Eigen::Vector3d(1, 2, 3));
  const Shape& sphere = r.link("upper").shapes.at(0);
  CHECK(geometry_get<Sphere>(sphere.geometry).radius == 0.25);
  REQUIRE(sphere.appearance.material);
  CHECK(sphere.appearance.material->transparency == 0.5);
}

TEST_CASE("urdf import: mesh scale, package:// through --package-path and package.xml, and a missing mesh") {
  const fs::path dir = fs::temp_directory_path() / "bodyfmt_urdf_import_meshes";
  fs::remove_all(dir);
  fs::create_directories(dir / "ws/my_robot/meshes");
  fs::create_directories(dir / "ws/my_robot/urdf");
  std::ofstream(dir / "ws/my_robot/package.xml") << "<package><name>my_robot</name></package>\n";
  std::ofstream(dir / "ws/my_robot/meshes/a.stl") << "solid a\nendsolid a\n";
  const std::string urdf = R"(<robot name="m">
  <link name="a">
    <visual><geometry><mesh filename="package://my_robot/meshes/a.stl" scale="2 3 4"/></geometry></visual>
    <visual><geometry><mesh filename="../meshes/a.stl"/></geometry></visual>
    <collision><geometry><mesh filename="package://other/meshes/b.stl"/></geometry></collision>
  </link>
</robot>)";
  UrdfImportOptions options;
  options.output_folder = dir / "out";
  LoadResult r = import_text(urdf, (dir / "ws/my_robot/urdf/m.urdf").string(), options);
  const Diagnostic missing = r.take("import-mesh");
  CHECK(pos(missing) == Pos{5, 32});
  // The message names the URI and every place searched, the nearest folders first.
  CHECK(missing.message.find("package://other/meshes/b.stl") != std::string::npos);
  CHECK(missing.message.find("package.xml naming 'other' in " + (dir / "ws/my_robot/urdf").string()) !=
        std::string::npos);
  r.expect_clean();
  const Link& a = r.link("a");
  REQUIRE(a.shapes.size() == 3);
  const auto& mesh = geometry_get<MeshResource>(a.shapes[0].geometry);
  CHECK(mesh.uri == "../ws/my_robot/meshes/a.stl");  // relative to the output folder
  CHECK(a.shapes[0].X_LS.linear() == Eigen::Matrix3d(Eigen::Vector3d(2, 3, 4).asDiagonal()));
  CHECK(geometry_get<MeshResource>(a.shapes[1].geometry).uri == "../ws/my_robot/meshes/a.stl");

  // --package-path finds a package by its folder.
  options.package_paths = {(dir / "ws").string()};
  LoadResult with_path = import_text(urdf, (dir / "elsewhere.urdf").string(), options);
  CHECK(with_path.count("import-mesh") == 2);  // ../meshes/a.stl and 'other'
  const auto& found = geometry_get<MeshResource>(with_path.link("a").shapes[0].geometry);
  CHECK(found.resolved_path == (dir / "ws/my_robot/meshes/a.stl").string());
  fs::remove_all(dir);
}

TEST_CASE("urdf import: losses are reported with their kind at their line") {
  LoadResult r = import_text(R"(
<robot name="l">
  <link name="a"/>
  <link name="b"/>
  <link name="c"/>
  <joint name="j1" type="continuous">
    <parent link="a"/><child link="b"/>
    <dynamics damping="0.5"/>
  </joint>
  <joint name="j2" type="planar">
    <parent link="b"/><child link="c"/>
    <mimic joint="j1"/>
  </joint>
  <transmission name="t"/>
  <gazebo reference="a"/>
</robot>
)");
  // <transmission> and <gazebo> are seen in the first pass over <robot>, joints in the tree walk.
  CHECK(pos(r.take("export-loss")) == Pos{13, 3});
  CHECK(pos(r.take("export-loss")) == Pos{14, 3});
  Diagnostic dynamics = r.take("export-loss");
  CHECK(pos(dynamics) == Pos{7, 5});
  CHECK(dynamics.category == "dynamics");
  Diagnostic planar = r.take("export-loss");
  CHECK(pos(planar) == Pos{9, 20});
  CHECK(planar.category == "joints");
  Diagnostic mimic = r.take("export-loss");
  CHECK(pos(mimic) == Pos{11, 5});
  CHECK(mimic.category == "joints");
  r.expect_clean();
  CHECK(r.link("b").joint_range_upper == kUnlimited);  // continuous
  CHECK(r.link("c").joint_type == JointType::kFixed);
}

TEST_CASE("urdf import: located structure errors") {
  SUBCASE("not well-formed") {
    LoadResult r = import_text("<robot name=\"x\">\n  <link name=\"a\">\n</robot>\n");
    // tinyxml2 reports the mismatched </robot> at the start of the <link> left open.
    CHECK(r.take("import-syntax").location.line == 2);
    r.expect_clean();
    CHECK_FALSE(r.model);
  }
  SUBCASE("a joint names a missing link") {
    LoadResult r = import_text(R"(
<robot name="x">
  <link name="a"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="nope"/></joint>
</robot>
)");
    CHECK(pos(r.take("import-structure")) == Pos{3, 57});
    r.expect_clean();
  }
  SUBCASE("two roots") {
    LoadResult r = import_text(R"(
<robot name="x">
  <link name="a"/>
  <link name="b"/>
</robot>
)");
    CHECK(pos(r.take("import-structure")) == Pos{3, 9});
    r.expect_clean();
  }
  SUBCASE("two roots on one line: the second <link> of the line") {
    LoadResult r = import_text(R"(
<robot name="x">
  <link name="a"/><link name="b"/>
</robot>
)");
    CHECK(pos(r.take("import-structure")) == Pos{2, 25});
    r.expect_clean();
  }
  SUBCASE("a cycle below the root") {
    LoadResult r = import_text(R"(
<robot name="x">
  <link name="root"/><link name="a"/><link name="b"/>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint>
</robot>
)");
    const Diagnostic d = r.take("import-structure");
    CHECK(pos(d) == Pos{4, 3});
    r.expect_clean();
  }
  SUBCASE("negative mass and inertia") {
    LoadResult r = import_text(R"(
<robot name="x">
  <link name="a"><inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="-2" iyz="0" izz="1"/></inertial></link>
</robot>
)");
    CHECK(pos(r.take("import-mass")) == Pos{2, 34});
    CHECK(pos(r.take("import-mass")) == Pos{2, 79});
    r.expect_clean();
  }
  SUBCASE("bad numbers and joint types") {
    LoadResult r = import_text(R"(
<robot name="x">
  <link name="a"/><link name="b"/>
  <joint name="j" type="hinge"><parent link="a"/><child link="b"/><origin xyz="0 nan 1"/></joint>
</robot>
)");
    CHECK(pos(r.take("import-value")) == Pos{3, 75});
    CHECK(pos(r.take("import-value")) == Pos{3, 19});
    r.expect_clean();
  }
}

TEST_CASE("urdf import: a world link with a fixed joint fixes the root") {
  LoadResult r = import_text(R"(
<robot name="w">
  <link name="world"/>
  <link name="base"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/><origin xyz="1 2 3"/></joint>
</robot>
)");
  r.expect_clean();
  REQUIRE(r.m().links.size() == 1);
  CHECK(r.m().links[0].name == "base");
  CHECK(r.m().links[0].joint_type == JointType::kFixed);
  CHECK(r.m().links[0].X_PL.translation() == Eigen::Vector3d(1, 2, 3));
}

TEST_CASE("urdf import: a world link keeps its joint's name and origin, a floating one frees the root") {
  LoadResult r = import_text(R"(
<robot name="w">
  <link name="world"/>
  <link name="base"/>
  <joint name="float" type="floating"><parent link="world"/><child link="base"/><origin xyz="0 0 1"/></joint>
</robot>
)");
  r.expect_clean();
  REQUIRE(r.m().links.size() == 1);
  CHECK(r.m().links[0].joint_type == JointType::kFree);
  CHECK(r.m().links[0].joint_name == "float");
  CHECK(r.m().links[0].X_PL.translation() == Eigen::Vector3d(0, 0, 1));
}

TEST_CASE("urdf import: a world link that is not empty is folded, its content is reported at its line") {
  LoadResult r = import_text(R"(
<robot name="w">
  <link name="world"><visual><geometry><box size="9 9 1"/></geometry></visual></link>
  <link name="base"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
</robot>
)");
  const Diagnostic d = r.take("export-loss");
  CHECK(pos(d) == Pos{2, 22});
  CHECK(d.category == "geometry");
  r.expect_clean();
  REQUIRE(r.m().links.size() == 1);
  CHECK(r.m().links[0].name == "base");
  CHECK(r.m().links[0].joint_type == JointType::kFixed);
  CHECK(r.m().links[0].joint_name == "fix");
}

TEST_CASE("urdf import: a world link on a planar joint stays a link, the planar joint is reported") {
  LoadResult r = import_text(R"(
<robot name="w">
  <link name="world"/>
  <link name="base"/>
  <joint name="plane" type="planar"><parent link="world"/><child link="base"/></joint>
</robot>
)");
  const Diagnostic d = r.take("export-loss");
  CHECK(pos(d) == Pos{4, 23});
  CHECK(d.category == "joints");
  r.expect_clean();
  REQUIRE(r.m().links.size() == 2);
  CHECK(r.m().links[0].name == "world");
  CHECK(r.link("base").joint_type == JointType::kFixed);
}

TEST_CASE("urdf import: conventions outside the URDF spec are read as ROS tools and simulators read them") {
  LoadResult r = import_text(R"(
<robot name="c">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" iyy="2" izz="3"/></inertial>
    <visual><geometry><box size="1 1 1"/><sphere radius="1"/></geometry></visual>
    <collision><geometry><sphere radius="0"/></geometry></collision>
    <collision><geometry><capsule radius="0.1" length="0.5"/></geometry></collision>
  </link>
  <link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
</robot>
)");
  // ixy, ixz and iyz are missing: read as 0, one warning each at the <inertia>.
  for (int i = 0; i < 3; ++i) CHECK(pos(r.take("import-convention")) == Pos{3, 32});
  CHECK(pos(r.take("import-convention")) == Pos{4, 42});  // the second shape, ignored
  const Diagnostic zero = r.take("export-loss");          // radius 0: Choreonoid refuses it
  CHECK(pos(zero) == Pos{5, 34});
  CHECK(zero.category == "geometry");
  CHECK(pos(r.take("import-convention")) == Pos{6, 26});   // <capsule>
  CHECK(pos(r.take("import-convention")) == Pos{10, 12});  // lower > upper
  r.expect_clean();
  const Link& a = r.link("a");
  CHECK(a.mass_contributions.at(0).inertia == Eigen::Vector3d(1, 2, 3).asDiagonal().toDenseMatrix());
  REQUIRE(a.shapes.size() == 2);
  CHECK(geometry_get<Box>(a.shapes[0].geometry).size == Eigen::Vector3d(1, 1, 1));
  const Capsule& capsule = geometry_get<Capsule>(a.shapes[1].geometry);
  CHECK(capsule.radius == 0.1);
  CHECK(capsule.height == 0.5);
  CHECK(r.link("b").joint_range_lower == 1);
  CHECK(r.link("b").joint_range_upper == -1);
}

}  // namespace
}  // namespace bodyfmt::test
