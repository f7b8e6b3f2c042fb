// Choreonoid scene files (.scen) named by a Resource node (body-format-spec §9.2): their shapes
// join the link with their transforms, in the scene file's own angle unit, located in the
// scene file; hostile scene files are bounded. Every expected pose and box below is worked
// out by hand from the files in tests/data/load/scene (each test says how).

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/load_helpers.h"

namespace fs = std::filesystem;
using bodyfmt::test::LoadResult;
using bodyfmt::test::pos;
using bodyfmt::test::Pos;

namespace {

const std::string kData = std::string(BODYFMT_TEST_DATA_DIR) + "/load/scene/";

LoadResult load_file(const std::string& path, bodyfmt::LoadOptions options = {}) {
  bodyfmt::CollectingSink sink;
  LoadResult result;
  result.model = bodyfmt::load_body(path, options, sink);
  result.diagnostics = sink.diagnostics();
  return result;
}

std::string file_name(const bodyfmt::SourceLocation& at) { return fs::path(at.file.str()).filename().string(); }

Eigen::Matrix3d columns(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const Eigen::Vector3d& z) {
  Eigen::Matrix3d m;
  m << x, y, z;
  return m;
}

/// A body file whose one link names `uri` by a Resource node.
std::string body_naming(const std::string& uri) {
  return "format: ChoreonoidBody\nformat_version: 2.0\nname: B\nlinks:\n"
         "  - {name: BASE, mass: 1, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1], elements: [{type: Resource, uri: " +
         uri + "}]}\n";
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("bodyfmt_scene_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

TEST_CASE("load: a scene file's primitives and TriangleMesh join the link with their transforms") {
  auto r = load_file(kData + "primitives.body");
  const bodyfmt::Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 4);
  // The Resource node moves the scene up by 2.
  const auto& box = base.shapes[0];
  REQUIRE(bodyfmt::geometry_is<bodyfmt::Box>(box.geometry));
  CHECK(bodyfmt::geometry_get<bodyfmt::Box>(box.geometry).size.isApprox(Eigen::Vector3d(0.2, 0.4, 0.6)));
  CHECK(box.X_LS.translation().isApprox(Eigen::Vector3d(1, 0, 2)));
  CHECK(box.X_LS.linear().isApprox(Eigen::Matrix3d::Identity()));
  CHECK(file_name(box.source) == "primitives.scen");
  CHECK(pos(box.source) == Pos{5, 5});
  REQUIRE(bodyfmt::geometry_is<bodyfmt::Sphere>(base.shapes[1].geometry));
  CHECK(base.shapes[1].X_LS.translation().isApprox(Eigen::Vector3d(0, 0, 2)));
  // Transform (0,0,1), 90 degrees about Z, then the Shape's own (1,0,0): Rz90 (1,0,0) = (0,1,0).
  const auto& cylinder = base.shapes[2];
  REQUIRE(bodyfmt::geometry_is<bodyfmt::Cylinder>(cylinder.geometry));
  CHECK(cylinder.X_LS.translation().isApprox(Eigen::Vector3d(0, 1, 3)));
  CHECK(cylinder.X_LS.linear().isApprox(columns({0, 1, 0}, {-1, 0, 0}, {0, 0, 1})));
  CHECK(pos(cylinder.source) == Pos{14, 9});
  const auto& mesh = base.shapes[3];
  REQUIRE(bodyfmt::geometry_is<bodyfmt::TriangleMeshGeometry>(mesh.geometry));
  CHECK(bodyfmt::geometry_get<bodyfmt::TriangleMeshGeometry>(mesh.geometry).vertices.size() == 3);
  CHECK(pos(mesh.source) == Pos{19, 9});
  // Box x 0.9..1.1; sphere radius 0.5 about (0,0,2); cylinder (Y axis turned to -X) about
  // (0,1,3): x -0.2..0.2, y 0.9..1.1, z 2.9..3.1; triangle x 0..1, y 0..2 at z 2.
  bodyfmt::CollectingSink sink;
  const auto bounds = bodyfmt::compute_link_bounds(r.m(), sink);
  CHECK(bounds[0].visual.min.isApprox(Eigen::Vector3d(-0.5, -0.5, 1.5)));
  CHECK(bounds[0].visual.max.isApprox(Eigen::Vector3d(1.1, 2.0, 3.1)));
  r.expect_clean();
}

TEST_CASE("load: a radian scene file inside a degree body, each read in its own unit") {
  auto r = load_file(kData + "units_degree_body.body");
  // The body turns 90 degrees about Z; the scene 1.5707963 rad about X, then (0,1,0):
  // Rx90 (0,1,0) = (0,0,1), Rz90 (0,0,1) = (0,0,1); Rz90 Rx90 sends x to y, y to z, z to x.
  const bodyfmt::Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 1);
  CHECK(base.shapes[0].X_LS.translation().isApprox(Eigen::Vector3d(0, 0, 1)));
  CHECK(base.shapes[0].X_LS.linear().isApprox(columns({0, 1, 0}, {0, 0, 1}, {1, 0, 0})));
  // formatVersion and angleUnit are the legacy spellings, reported in the scene file.
  auto legacy = r.take("load-legacy-key");
  CHECK(file_name(legacy.location) == "radian.scen");
  CHECK(pos(legacy) == Pos{2, 1});
  CHECK(pos(r.take("load-legacy-key")) == Pos{3, 1});
  r.expect_clean();
}

TEST_CASE("load: a degree scene file inside a radian body, whose upgrade leaves the scene alone") {
  auto r = load_file(kData + "units_radian_body.body");
  // The body turns pi about Z; the scene 90 degrees about Y, then (0,0,1): Ry90 (0,0,1) =
  // (1,0,0), Rz180 (1,0,0) = (-1,0,0). Rz180 Ry90 sends x to -z, y to -y, z to -x.
  const bodyfmt::Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 1);
  CHECK(base.shapes[0].X_LS.translation().isApprox(Eigen::Vector3d(-1, 0, 0)));
  CHECK(base.shapes[0].X_LS.linear().isApprox(columns({0, 0, -1}, {0, -1, 0}, {-1, 0, 0})));
  // The upgrade to 2.0 rewrites the body's one angle (and its header), none of the scene's.
  const auto upgrade = r.take("load-format-upgrade");
  REQUIRE(upgrade.fixes.size() == 3);
  for (const bodyfmt::FixIt& fix : upgrade.fixes)
    CHECK(fs::path(fix.file.str()).filename() == "units_radian_body.body");
  CHECK(upgrade.fixes[2].replacement == "180");
  r.expect_clean();
}

TEST_CASE("load: nested transforms and a nested scene file in radians, inside a Visual node") {
  auto r = load_file(kData + "nested.body");
  const bodyfmt::Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 2);
  // T1 = T2 = translate (1,0,0), turn 90 about Z. Box: T2 (1,0,0) = (1,1,0), T1 (1,1,0) = (0,1,0);
  // turned 180 about Z.
  const auto& box = base.shapes[0];
  CHECK(box.X_LS.translation().isApprox(Eigen::Vector3d(0, 1, 0)));
  CHECK(box.X_LS.linear().isApprox(columns({-1, 0, 0}, {0, -1, 0}, {0, 0, 1})));
  // child.scen (radians): pi about Z, then (2,0,0) gives (-2,0,0); the Resource adds (0,0,1):
  // (-2,0,1); T2: (1,-2,1); T1: (3,1,1). Turns 90 + 90 + 180 = 360: identity.
  const auto& capsule = base.shapes[1];
  REQUIRE(bodyfmt::geometry_is<bodyfmt::Capsule>(capsule.geometry));
  CHECK(capsule.X_LS.translation().isApprox(Eigen::Vector3d(3, 1, 1)));
  CHECK(capsule.X_LS.linear().isApprox(Eigen::Matrix3d::Identity()));
  CHECK(file_name(capsule.source) == "child.scen");
  CHECK(pos(capsule.source) == Pos{8, 9});
  for (const bodyfmt::Shape& shape : base.shapes) {
    CHECK(shape.visual);
    CHECK_FALSE(shape.collision);
  }
  r.expect_clean();
}

TEST_CASE("load: a scene file's length unit scales its lengths, scale_orientation turns the scale axes") {
  auto r = load_file(kData + "scaled.body");
  const bodyfmt::Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 1);
  // millimetres: translation 1000 is 1 m, the box 100 is 0.1 m; scale [2,1,1] along axes
  // turned 90 about Z is Rz90 diag(2,1,1) Rz90^T = diag(1,2,1).
  CHECK(base.shapes[0].X_LS.translation().isApprox(Eigen::Vector3d(1, 0, 0)));
  CHECK(base.shapes[0].X_LS.linear().isApprox(Eigen::Vector3d(0.001, 0.002, 0.001).asDiagonal().toDenseMatrix()));
  bodyfmt::CollectingSink sink;
  const auto bounds = bodyfmt::compute_link_bounds(r.m(), sink);
  CHECK(bounds[0].visual.min.isApprox(Eigen::Vector3d(0.95, -0.1, -0.05)));
  CHECK(bounds[0].visual.max.isApprox(Eigen::Vector3d(1.05, 0.1, 0.05)));
  r.expect_clean();
}

TEST_CASE("load: a scene file as a Shape's geometry gives its one shape the Shape's place and appearance") {
  auto r = load_file(kData + "geometry.body");
  // primitives.scen has four shapes: Choreonoid refuses it as a geometry.
  auto d = r.take("scene-unsupported");
  CHECK(file_name(d.location) == "geometry.body");
  CHECK(pos(d) == Pos{16, 41});
  r.expect_clean();
  const bodyfmt::Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 1);
  const bodyfmt::Shape& plate = base.shapes[0];
  CHECK(plate.name == "PLATE");
  REQUIRE(bodyfmt::geometry_is<bodyfmt::Box>(plate.geometry));
  CHECK(bodyfmt::geometry_get<bodyfmt::Box>(plate.geometry).size.isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  CHECK(plate.X_LS.translation().isApprox(Eigen::Vector3d(0, 0, 1)));
  // The Shape node's blue, not the scene file's red.
  REQUIRE(plate.appearance.material);
  CHECK(plate.appearance.material->diffuse_color.isApprox(Eigen::Vector3d(0, 0, 1)));
}

TEST_CASE("load: what a scene file cannot hold is reported at its line in the scene file") {
  auto r = load_file(kData + "errors.body");
  auto typo = r.take("load-unknown-model-key");
  CHECK(file_name(typo.location) == "errors.scen");
  CHECK(pos(typo) == Pos{5, 5});
  auto rigid = r.take("load-unknown-node-type");  // a body node type, not a scene one
  CHECK(file_name(rigid.location) == "errors.scen");
  CHECK(pos(rigid) == Pos{7, 11});
  CHECK(pos(r.take("geometry-unknown-type")) == Pos{10, 22});
  CHECK(pos(r.take("load-scene-node")) == Pos{11, 5});   // a scene light, not a device
  CHECK(pos(r.take("load-type")) == Pos{13, 22});        // `elements` keyed by `type`
  CHECK(pos(r.take("load-ignored-key")) == Pos{17, 5});  // a Node is empty: its elements are not read
  r.expect_clean();
  // The box (at the origin: its translation is misspelt) and the last sphere are kept.
  const bodyfmt::Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 2);
  CHECK(base.shapes[0].X_LS.translation().isApprox(Eigen::Vector3d::Zero()));
  CHECK(pos(base.shapes[1].source) == Pos{14, 5});
  CHECK(r.m().devices.empty());
}

TEST_CASE("load: a scene file's header is checked as Choreonoid's scene loader checks it") {
  auto r = load_file(kData + "headers.body");
  auto version = r.take("scene-header");
  CHECK(file_name(version.location) == "bad_version.scen");
  CHECK(pos(version) == Pos{2, 17});
  auto radian = r.take("scene-header");
  CHECK(file_name(radian.location) == "radian_in_2.scen");
  CHECK(pos(radian) == Pos{3, 13});
  auto missing = r.take("scene-header");
  CHECK(file_name(missing.location) == "no_version.scen");
  CHECK(pos(missing) == Pos{1, 1});
  auto format = r.take("scene-format-name");
  CHECK(pos(format) == Pos{1, 9});
  r.expect_clean();
  CHECK(r.link("BASE").shapes.empty());  // Choreonoid loads nothing from any of them
}

TEST_CASE("load: an empty scene, a YAML resource in a scene file and a node a scene file lacks") {
  auto r = load_file(kData + "unsupported.body");
  auto empty = r.take("scene-empty");
  CHECK(file_name(empty.location) == "empty.scen");
  CHECK(pos(empty) == Pos{3, 8});
  // Choreonoid reads a YAML resource in a scene file (tests/data/body_choreonoid/
  // scene_yaml_resource.ref.yaml, made by Choreonoid), and refuses a node: that names no node
  // ("Fragment ... is not found"): primitives.scen has no BOX.
  auto node = r.take("mesh-node-not-found");
  CHECK(file_name(node.location) == "unsupported.body");
  CHECK(pos(node) == Pos{12, 54});
  r.expect_clean();
  // names_yaml.scen's YAML part (parts.yaml's PART, a 1 m box) and its sphere.
  const bodyfmt::Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 2);
  CHECK(bodyfmt::geometry_is<bodyfmt::Box>(base.shapes[0].geometry));
  CHECK(bodyfmt::geometry_is<bodyfmt::Sphere>(base.shapes[1].geometry));
}

TEST_CASE("load: scene files naming themselves or each other stop at the repeated file") {
  auto r = load_file(kData + "cycles.body");
  auto self = r.take("scene-recursion");
  CHECK(file_name(self.location) == "self.scen");
  CHECK(pos(self) == Pos{5, 27});
  CHECK(self.message.find("self.scen -> self.scen") != std::string::npos);
  auto mutual = r.take("scene-recursion");
  CHECK(file_name(mutual.location) == "cycle_b.scen");
  CHECK(pos(mutual) == Pos{5, 27});
  CHECK(mutual.message.find("cycle_a.scen -> cycle_b.scen -> cycle_a.scen") != std::string::npos);
  r.expect_clean();
  // self's sphere, cycle_a's box and cycle_b's sphere, once each.
  CHECK(r.link("BASE").shapes.size() == 3);
}

TEST_CASE("load: hostile scene files: deep nesting, a multiplying include, a FIFO, a file over the limit") {
  TempDir dir;
  SUBCASE("twenty scene files each naming the next stop at the nesting limit") {
    for (int i = 0; i < 20; ++i)
      write(dir.path / ("s" + std::to_string(i) + ".scen"),
            "format_version: 2.0\nscene:\n  - {type: Shape, geometry: {type: Sphere, radius: 1}}\n"
            "  - {type: Resource, uri: s" +
                std::to_string(i + 1) + ".scen}\n");
    write(dir.path / "main.body", body_naming("s0.scen"));
    auto r = load_file((dir.path / "main.body").string());
    auto d = r.take("scene-recursion");
    CHECK(file_name(d.location) == "s15.scen");  // s0 .. s15 are read: 16 files
    CHECK(pos(d) == Pos{4, 27});
    r.expect_clean();
    CHECK(r.link("BASE").shapes.size() == 16);
  }
  SUBCASE("two scene files of 60 nested Transforms each are deeper together than one document may be") {
    // Each file: 60 Transforms, one inside the next's elements, around a Resource (a.scen) or
    // a Shape (b.scen). Depths: 1 (the innermost mapping; 2 for the Shape and its geometry)
    // + 2 x 60 + the scene list + the root = 123 and 124; together 247 > 200 (the default).
    auto nested = [](const std::string& innermost) {
      std::string text = "format_version: 2.0\nscene:\n", indent = "  ";
      for (int i = 0; i < 60; ++i) {
        text += indent + "- type: Transform\n" + indent + "  elements:\n";
        indent += "    ";
      }
      return text + indent + "- " + innermost + "\n";
    };
    write(dir.path / "a.scen", nested("{type: Resource, uri: b.scen}"));
    write(dir.path / "b.scen", nested("{type: Shape, geometry: {type: Sphere}}"));
    write(dir.path / "main.body", body_naming("a.scen"));
    auto r = load_file((dir.path / "main.body").string());
    auto d = r.take("scene-recursion");
    // Line 2 + 2 x 60 + 1; the uri after 2 + 4 x 60 spaces and "- {type: Resource, uri: ".
    CHECK(file_name(d.location) == "a.scen");
    CHECK(pos(d) == Pos{123, 267});
    r.expect_clean();
    CHECK(r.link("BASE").shapes.empty());
    write(dir.path / "main.body", body_naming("b.scen"));  // one alone is within the bound
    r = load_file((dir.path / "main.body").string());
    r.expect_clean();
    CHECK(r.link("BASE").shapes.size() == 1);
  }
  SUBCASE("a file named 10 times by a file named 10 times runs out of the node budget") {
    std::string ten = "format_version: 2.0\nscene:\n";
    for (int i = 0; i < 10; ++i) ten += "  - {type: Resource, uri: leaf.scen}\n";
    write(dir.path / "ten.scen", ten);
    write(dir.path / "leaf.scen", "format_version: 2.0\nscene: [{type: Shape, geometry: {type: Sphere}}]\n");
    std::string hundred = "format_version: 2.0\nscene:\n";
    for (int i = 0; i < 10; ++i) hundred += "  - {type: Resource, uri: ten.scen}\n";
    write(dir.path / "hundred.scen", hundred);
    write(dir.path / "main.body", body_naming("hundred.scen"));
    bodyfmt::LoadOptions options;
    auto r = load_file((dir.path / "main.body").string(), options);
    r.expect_clean();
    CHECK(r.link("BASE").shapes.size() == 100);
    // Values count, keys do not: leaf.scen is 7 nodes (the mapping, 2.0, the list, the Shape
    // mapping, Shape, the geometry mapping, Sphere); ten.scen and hundred.scen 3 + 10 x 3 = 33:
    // 33 + 10 x (33 + 10 x 7) = 1063 in all, one over a budget of 1062.
    options.max_expanded_yaml_nodes = 1062;
    r = load_file((dir.path / "main.body").string(), options);
    auto d = r.take("scene-expansion");
    CHECK(file_name(d.location) == "ten.scen");
    r.expect_clean();
    CHECK(r.link("BASE").shapes.size() < 100);
  }
  SUBCASE("a FIFO named as a scene file is refused without opening it") {
    REQUIRE(::mkfifo((dir.path / "pipe.scen").c_str(), 0600) == 0);  // no writer: opening would block
    write(dir.path / "main.body", body_naming("pipe.scen"));
    auto r = load_file((dir.path / "main.body").string());
    auto d = r.take("resource-missing");
    CHECK(pos(d) == Pos{5, 98});
    r.expect_clean();
  }
  SUBCASE("a scene file over --max-file-size is refused") {
    write(dir.path / "big.scen",
          "format_version: 2.0\nscene: [{type: Shape, geometry: {type: Sphere}}]\n" + std::string(200, '#') + "\n");
    write(dir.path / "main.body", body_naming("big.scen"));
    bodyfmt::LoadOptions options;
    options.max_file_bytes = 200;
    auto r = load_file((dir.path / "main.body").string(), options);
    auto d = r.take("resource-missing");
    CHECK(d.message.find("200") != std::string::npos);
    r.expect_clean();
  }
}
