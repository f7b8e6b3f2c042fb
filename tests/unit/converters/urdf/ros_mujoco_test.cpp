// body2urdf from the user's side: URDFs that ROS (package:// URIs) and MuJoCo (mesh folders,
// mesh formats) use as they are. Each case runs the tool and reads what it wrote with urdfdom
// and MuJoCo 2.2.2 (mj_loadXML), the programs those users have.
#include <bodyfmt/converters/mesh_writer.h>

#include <doctest/doctest.h>

#include <mujoco/mujoco.h>
#include <urdf_parser/urdf_parser.h>
#include "support/export_helpers.h"
#include "support/run_command.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace fs = std::filesystem;
using bodyfmt::test::fresh_dir;
using bodyfmt::test::read;
using bodyfmt::test::run_command;

namespace {

const std::string kTool = BODYFMT_BODY2URDF;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

bodyfmt::TriangleMesh tetrahedron(double offset) {
  bodyfmt::TriangleMesh m;
  m.vertices = {{offset, 0, 0}, {offset + 0.1, 0, 0}, {offset, 0.1, 0}, {offset, 0, 0.1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

/// In `dir`/src: model.body with a binary STL on BASE, a red DAE on ARM, an ASCII STL and a Cone
/// (a generated mesh) on TIP.
fs::path mesh_model(const fs::path& dir) {
  write(dir / "src" / "parts" / "box.stl", bodyfmt::converters::write_stl(tetrahedron(0)));
  bodyfmt::Material red;
  red.diffuse_color = Eigen::Vector3d(1, 0, 0);
  std::string error;
  auto dae = bodyfmt::converters::write_dae(tetrahedron(0.2), red, "arm", error);
  REQUIRE(dae);
  write(dir / "src" / "parts" / "arm.dae", *dae);
  write(dir / "src" / "parts" / "plate.stl",
        "solid plate\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\nendloop\n"
        "endfacet\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 0.1 0\nvertex 0.1 0 0\nendloop\n"
        "endfacet\nendsolid plate\n");
  const fs::path body = dir / "src" / "model.body";
  write(body, R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
name: MeshArm
links:
  - name: BASE
    joint_type: fixed
    mass: 1
    inertia: [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
    elements:
      - { type: Shape, geometry: { type: Resource, uri: "parts/box.stl" } }
  - name: ARM
    parent: BASE
    translation: [0, 0, 0.1]
    joint_type: revolute
    joint_axis: [0, 0, 1]
    joint_range: [-90, 90]
    max_joint_velocity: 90
    max_joint_effort: 10
    mass: 1
    inertia: [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
    elements:
      - { type: Shape, geometry: { type: Resource, uri: "parts/arm.dae" } }
  - name: TIP
    parent: ARM
    translation: [0, 0, 0.2]
    joint_type: revolute
    joint_axis: [0, 1, 0]
    joint_range: [-90, 90]
    max_joint_velocity: 90
    max_joint_effort: 10
    mass: 0.5
    inertia: [0.001, 0, 0, 0, 0.001, 0, 0, 0, 0.001]
    elements:
      - { type: Shape, geometry: { type: Resource, uri: "parts/plate.stl" } }
      - { type: Shape, geometry: { type: Cone, radius: 0.02, height: 0.05 } }
)");
  return body;
}

/// The mesh file names of every <visual> and <collision>, as urdfdom reads them.
std::multiset<std::string> mesh_filenames(const std::string& urdf_text) {
  std::multiset<std::string> out;
  auto model = ::urdf::parseURDF(urdf_text);
  REQUIRE(model);
  for (const auto& [name, link] : model->links_) {
    for (const auto& c : link->collision_array)
      if (auto mesh = std::dynamic_pointer_cast<::urdf::Mesh>(c->geometry)) out.insert(mesh->filename);
    for (const auto& v : link->visual_array)
      if (auto mesh = std::dynamic_pointer_cast<::urdf::Mesh>(v->geometry)) out.insert(mesh->filename);
  }
  return out;
}

/// The triangle count of a binary STL, after checking that the file is one (84 + 50 n bytes).
std::uint32_t stl_triangles(const fs::path& stl) {
  const std::string bytes = read(stl);
  REQUIRE(bytes.size() >= 84);
  std::uint32_t n = 0;
  for (int i = 3; i >= 0; --i) n = (n << 8) | static_cast<unsigned char>(bytes[80 + static_cast<std::size_t>(i)]);
  REQUIRE(bytes.size() == 84 + 50 * static_cast<std::size_t>(n));
  return n;
}

std::set<std::string> files_in(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.insert(e.path().filename().string());
  return names;
}

const char* kPackageXml = R"(<?xml version="1.0"?>
<package format="3">
  <name>my_robot</name>
  <version>0.1.0</version>
  <description>bodyfmt test package</description>
  <maintainer email="nobody@example.com">nobody</maintainer>
  <license>MIT</license>
</package>
)";

}  // namespace

TEST_CASE("urdf user: copied meshes are written in --mesh-format, ASCII STL as binary") {
  const fs::path dir = fresh_dir("mesh_format");
  const fs::path body = mesh_model(dir);
  const std::string tool = "'" + kTool + "' -q '" + body.string() + "'";
  // STL (the default): the DAE and the ASCII STL are converted, the binary STL copied as it is.
  REQUIRE(run_command(tool + " -o stl/robot.urdf --copy-meshes", dir.string()).status == 0);
  const fs::path stl = dir / "stl" / "meshes" / "robot";
  CHECK(files_in(stl) == std::set<std::string>{".bodyfmt-export", "arm.stl", "box.stl", "plate.stl", "TIP_shape1.stl"});
  CHECK(read(stl / "box.stl") == read(dir / "src" / "parts" / "box.stl"));
  CHECK(stl_triangles(stl / "arm.stl") == 4);    // the DAE's 4 triangles
  CHECK(stl_triangles(stl / "plate.stl") == 2);  // the ASCII file's 2 facets
  // The DAE's red survives as the URDF material of ARM.
  const std::string urdf = read(dir / "stl" / "robot.urdf");
  CHECK(urdf.find("rgba=\"1 0 0 1\"") != std::string::npos);
  // DAE: the STLs are converted, the DAE copied as it is.
  REQUIRE(run_command(tool + " -o dae/robot.urdf --copy-meshes --mesh-format dae", dir.string()).status == 0);
  const fs::path dae = dir / "dae" / "meshes" / "robot";
  CHECK(files_in(dae) == std::set<std::string>{".bodyfmt-export", "arm.dae", "box.dae", "plate.dae", "TIP_shape1.dae"});
  CHECK(read(dae / "arm.dae") == read(dir / "src" / "parts" / "arm.dae"));
  // --reference-meshes: meshes are referenced where they are, in their own format.
  REQUIRE(run_command(tool + " -o ref/robot.urdf --reference-meshes", dir.string()).status == 0);
  const auto names = mesh_filenames(read(dir / "ref" / "robot.urdf"));
  CHECK(names.count("../src/parts/arm.dae") == 2);
  CHECK(names.count("../src/parts/box.stl") == 2);
  fs::remove_all(dir);
}

TEST_CASE("urdf user: --package-uri writes URIs relative to the package root that package.xml marks") {
  const fs::path dir = fresh_dir("package");
  const fs::path body = mesh_model(dir);
  write(dir / "pkg" / "package.xml", kPackageXml);
  const std::string tool = "'" + kTool + "' -q '" + body.string() + "'";
  // Every package URI must name an existing file once package://my_robot/ is the package root,
  // as ROS resolves it.
  auto check_resolvable = [&](const fs::path& urdf, const std::string& folder) {
    const auto names = mesh_filenames(read(urdf));
    REQUIRE(names.size() == 8);  // visual and collision of 4 shapes
    for (const std::string& name : names) {
      CAPTURE(name);
      REQUIRE(name.rfind("package://my_robot/" + folder + "/", 0) == 0);
      CHECK(fs::is_regular_file(dir / "pkg" / name.substr(std::string("package://my_robot/").size())));
    }
  };
  SUBCASE("meshes beside the URDF, in pkg/urdf/meshes/robot") {
    REQUIRE(run_command(tool + " -o pkg/urdf/robot.urdf --package-uri package://my_robot", dir.string()).status == 0);
    check_resolvable(dir / "pkg" / "urdf" / "robot.urdf", "urdf/meshes/robot");
  }
  SUBCASE("--mesh-folder ../meshes: the package's own meshes folder") {
    REQUIRE(run_command(tool + " -o pkg/urdf/robot.urdf --package-uri package://my_robot/ --mesh-folder ../meshes",
                        dir.string())
                .status == 0);
    check_resolvable(dir / "pkg" / "urdf" / "robot.urdf", "meshes");
    CHECK(!fs::exists(dir / "pkg" / "urdf" / "meshes"));
  }
  SUBCASE("usage errors: not package://, no package.xml, another package's name, a folder outside it") {
    const auto scheme = run_command(tool + " -o pkg/urdf/robot.urdf --package-uri my_robot", dir.string());
    CHECK(scheme.status == 2);
    CHECK(scheme.output.find("must be package://NAME") != std::string::npos);
    const auto none = run_command(tool + " -o elsewhere/robot.urdf --package-uri package://my_robot", dir.string());
    CHECK(none.status == 2);
    CHECK(none.output.find("needs the URDF inside a ROS package: no package.xml in") != std::string::npos);
    const auto other = run_command(tool + " -o pkg/urdf/robot.urdf --package-uri package://other", dir.string());
    CHECK(other.status == 2);
    CHECK(other.output.find("declares 'my_robot'") != std::string::npos);
    const auto outside = run_command(
        tool + " -o pkg/urdf/robot.urdf --package-uri package://my_robot --mesh-folder ../../x", dir.string());
    CHECK(outside.status == 2);
    CHECK(outside.output.find("--mesh-folder ../../x") != std::string::npos);
    CHECK(!fs::exists(dir / "pkg" / "urdf"));
    CHECK(!fs::exists(dir / "elsewhere"));
  }
  fs::remove_all(dir);
}

TEST_CASE("urdf user: by default every mesh URI resolves beside the URDF, or in the ROS package that holds it") {
  const fs::path dir = fresh_dir("portable");
  const fs::path body = mesh_model(dir);
  const std::string tool = "'" + kTool + "' -q '" + body.string() + "'";
  SUBCASE("no package.xml: copies beside the URDF, relative URIs that stay inside its folder") {
    REQUIRE(run_command(tool + " -o out/robot.urdf", dir.string()).status == 0);
    const auto names = mesh_filenames(read(dir / "out" / "robot.urdf"));
    REQUIRE(names.size() == 8);
    for (const std::string& name : names) {
      CAPTURE(name);
      CHECK(name.rfind("meshes/robot/", 0) == 0);
      CHECK(fs::is_regular_file(dir / "out" / name));
    }
    // The folder moved elsewhere still resolves: nothing points back into src/.
    fs::rename(dir / "out", dir / "moved");
    for (const std::string& name : names) CHECK(fs::is_regular_file(dir / "moved" / name));
  }
  SUBCASE("a package.xml above the URDF: package://NAME/ URIs, meshes copied into the package") {
    write(dir / "pkg" / "package.xml", kPackageXml);
    REQUIRE(run_command(tool + " -o pkg/urdf/robot.urdf", dir.string()).status == 0);
    const auto names = mesh_filenames(read(dir / "pkg" / "urdf" / "robot.urdf"));
    REQUIRE(names.size() == 8);
    for (const std::string& name : names) {
      CAPTURE(name);
      REQUIRE(name.rfind("package://my_robot/urdf/meshes/robot/", 0) == 0);
      CHECK(fs::is_regular_file(dir / "pkg" / name.substr(std::string("package://my_robot/").size())));
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("urdf user: a new export removes the meshes its previous export wrote and no longer uses, only those") {
  const fs::path dir = fresh_dir("stale");
  const fs::path body = mesh_model(dir);
  const std::string tool = "'" + kTool + "' -q '" + body.string() + "'";
  REQUIRE(run_command(tool + " -o out/robot.urdf", dir.string()).status == 0);
  const fs::path meshes = dir / "out" / "meshes" / "robot";
  REQUIRE(files_in(meshes) ==
          std::set<std::string>{".bodyfmt-export", "arm.stl", "box.stl", "plate.stl", "TIP_shape1.stl"});
  // A file of the user's in the folder, and a name the record gives to another export.
  write(meshes / "notes.txt", "mine\n");
  write(meshes / "other.stl", "another export's\n");
  {
    std::ofstream record(meshes / ".bodyfmt-export", std::ios::app);
    record << "other.stl\t../../other.urdf\n";
  }
  REQUIRE(run_command(tool + " -o out/robot.urdf --mesh-format dae", dir.string()).status == 0);
  CHECK(files_in(meshes) == std::set<std::string>{".bodyfmt-export", "arm.dae", "box.dae", "plate.dae",
                                                  "TIP_shape1.dae", "notes.txt", "other.stl"});
  const std::string record = read(meshes / ".bodyfmt-export");
  CHECK(record.find("box.stl") == std::string::npos);
  CHECK(record.find("other.stl\t../../other.urdf") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("urdf user: MuJoCo loads the exported URDF with its meshes in a folder") {
  const fs::path dir = fresh_dir("mujoco");
  const fs::path body = mesh_model(dir);
  const std::string tool = "'" + kTool + "' -q '" + body.string() + "'";
  // MuJoCo reads STL only: the DAE and the ASCII STL are copied as binary STL.
  REQUIRE(run_command(tool + " -o out/robot.urdf --copy-meshes", dir.string()).status == 0);
  char error[1000] = "";
  mjModel* m = mj_loadXML((dir / "out" / "robot.urdf").c_str(), nullptr, error, sizeof error);
  INFO(error);
  REQUIRE(m != nullptr);
  CHECK(m->nbody == 3);  // world (with BASE: MuJoCo fuses the fixed root into it), ARM, TIP
  CHECK(m->njnt == 2);
  CHECK(m->nmesh == 4);  // box, arm, plate, the cone
  mj_deleteModel(m);
  // Without the <mujoco> element MuJoCo strips the folder and finds no mesh: why it is on.
  REQUIRE(run_command(tool + " -o bare/robot.urdf --copy-meshes --no-mujoco", dir.string()).status == 0);
  CHECK(read(dir / "bare" / "robot.urdf").find("<mujoco>") == std::string::npos);
  error[0] = '\0';
  mjModel* bare = mj_loadXML((dir / "bare" / "robot.urdf").c_str(), nullptr, error, sizeof error);
  CHECK(bare == nullptr);
  CHECK(std::string(error).find("could not open STL file") != std::string::npos);
  if (bare) mj_deleteModel(bare);
  fs::remove_all(dir);
}
