// One package map (bodyfmt/package_map.h): the same package:// URI written in a .body file and in
// a URDF beside it resolves to the same file, under every search rule, and a URI none of them
// finds is reported by both readers. Expected paths are where this test put the files.
#include "urdf_reader.h"

#include <bodyfmt/load.h>
#include <bodyfmt/package_map.h>

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <unistd.h>

namespace bodyfmt::test {
namespace {

namespace fs = std::filesystem;

struct Tree {
  // One folder per test case and process: ctest runs the cases side by side.
  fs::path root;
  fs::path robot;      // package robot_description: folder and name differ
  fs::path referring;  // where the .body and the URDF are

  explicit Tree(const std::string& name)
      : root(fs::temp_directory_path() / ("bodyfmt_package_map_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(root);
    robot = root / "ws/src/robot_folder";
    referring = robot / "models";
    make(root / "ws/src/robot_folder/package.xml", "<package>\n  <name> robot_description </name>\n</package>\n");
    make(robot / "meshes/b.stl");
    make(root / "ws/src/pkg_a/package.xml", "<package><name>pkg_a</name></package>");
    make(root / "ws/src/pkg_a/meshes/a.stl");
    make(root / "paths/pkg_c/meshes/c.stl");  // --package-path paths: a folder per package
    make(root / "paths/declared/package.xml", "<package><name>pkg_x</name></package>");
    make(root / "paths/declared/x.stl");                     // --package-path to a package itself
    make(root / "ros/pkg_d/meshes/d.stl");                   // ROS_PACKAGE_PATH
    make(root / "ws/src/robot_folder/meshes/dir.stl/keep");  // a folder is not a mesh file
    fs::create_directories(referring);
  }
  ~Tree() { fs::remove_all(root); }

  static void make(const fs::path& file, const std::string& text = "solid s\nendsolid s\n") {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
  }
};

struct Resolved {
  std::string by_library, by_body, by_urdf;
  bool body_reported = false, urdf_reported = false;
};

Resolved resolve(const Tree& tree, const std::string& uri, bool use_ros_package_path) {
  Resolved r;
  PackageSearch search{
      {(tree.root / "paths").string(), (tree.root / "paths/declared").string()}, use_ros_package_path, tree.referring};
  r.by_library = find_package_file(uri, search).path;

  LoadOptions options;
  options.package_paths = search.package_paths;
  options.use_ros_package_path = use_ros_package_path;
  options.load_meshes = false;  // the URI is resolved all the same; the files are not meshes
  CollectingSink body_sink;
  const std::string body =
      "format: ChoreonoidBody\nformat_version: 2.0\nname: m\nlinks:\n  - name: a\n"
      "    joint_type: free\n    elements:\n      - type: Shape\n        geometry: { type: "
      "Resource, uri: \"" +
      uri + "\" }\n";
  if (auto model = load_body_string(body, (tree.referring / "m.body").string(), options, body_sink))
    if (!model->links.empty() && !model->links[0].shapes.empty())
      if (const auto* mesh = geometry_if<MeshResource>(model->links[0].shapes[0].geometry))
        r.by_body = mesh->resolved_path;
  r.body_reported = body_sink.has("load-uri");

  urdf_import::UrdfImportOptions import;
  import.package_paths = search.package_paths;
  import.use_ros_package_path = use_ros_package_path;
  import.output_folder = tree.referring;
  CollectingSink urdf_sink;
  const std::string urdf = "<robot name=\"m\"><link name=\"a\"><visual><geometry><mesh filename=\"" + uri +
                           "\"/></geometry></visual></link></robot>";
  if (auto model = urdf_import::import_urdf(urdf, (tree.referring / "m.urdf").string(), import, urdf_sink))
    if (!model->links.empty() && !model->links[0].shapes.empty())
      if (const auto* mesh = geometry_if<MeshResource>(model->links[0].shapes[0].geometry))
        r.by_urdf = mesh->resolved_path;
  r.urdf_reported = urdf_sink.has("import-mesh");
  return r;
}

TEST_CASE("package map: a .body file and a URDF resolve every package:// URI to the same file") {
  Tree tree("readers");
  const std::string ros_before = std::getenv("ROS_PACKAGE_PATH") ? std::getenv("ROS_PACKAGE_PATH") : "";
  ::setenv("ROS_PACKAGE_PATH", ("/nonexistent:" + (tree.root / "ros").string()).c_str(), 1);
  const struct {
    const char* uri;
    fs::path expected;  // empty: found by no rule
  } cases[] = {
      {"package://robot_description/meshes/b.stl", tree.robot / "meshes/b.stl"},   // package.xml above
      {"package://pkg_a/meshes/a.stl", tree.root / "ws/src/pkg_a/meshes/a.stl"},   // a sibling package
      {"package:///pkg_a/meshes/a.stl", tree.root / "ws/src/pkg_a/meshes/a.stl"},  // as found in the wild
      {"package://pkg_c/meshes/c.stl", tree.root / "paths/pkg_c/meshes/c.stl"},    // --package-path
      {"package://pkg_x/x.stl", tree.root / "paths/declared/x.stl"},               // a package path's package.xml
      {"package://pkg_d/meshes/d.stl", tree.root / "ros/pkg_d/meshes/d.stl"},      // ROS_PACKAGE_PATH
      {"package://robot_description/meshes/dir.stl", {}},                          // a folder
      {"package://missing/meshes/m.stl", {}},
      {"package://robot_description/", {}},
  };
  for (const auto& c : cases) {
    CAPTURE(c.uri);
    const Resolved r = resolve(tree, c.uri, true);
    CHECK(r.by_library == c.expected.string());
    CHECK(r.by_body == c.expected.string());
    CHECK(r.by_urdf == c.expected.string());
    CHECK(r.body_reported == c.expected.empty());
    CHECK(r.urdf_reported == c.expected.empty());
  }
  // --no-ros-package-path: both readers stop finding the ROS_PACKAGE_PATH package, and only it.
  const Resolved without_ros = resolve(tree, "package://pkg_d/meshes/d.stl", false);
  CHECK(without_ros.by_body.empty());
  CHECK(without_ros.by_urdf.empty());
  CHECK(without_ros.body_reported);
  CHECK(without_ros.urdf_reported);
  CHECK(resolve(tree, "package://pkg_c/meshes/c.stl", false).by_body ==
        (tree.root / "paths/pkg_c/meshes/c.stl").string());
  ::setenv("ROS_PACKAGE_PATH", ros_before.c_str(), 1);
  if (ros_before.empty()) ::unsetenv("ROS_PACKAGE_PATH");
}

TEST_CASE("package map: the ROS package a file is written into, and paths inside it") {
  Tree tree("writer");
  std::string why;
  const std::optional<RosPackage> package = find_ros_package(tree.referring, why);
  REQUIRE(package);
  CHECK(package->name == "robot_description");  // trimmed
  CHECK(package->root == tree.robot);
  CHECK(path_in_package(package->root, tree.robot / "meshes/b.stl") == std::optional<std::string>("meshes/b.stl"));
  CHECK_FALSE(path_in_package(package->root, tree.root / "ws/src/pkg_a/meshes/a.stl"));
  Tree::make(tree.root / "bad/package.xml", "<package><name></name></package>");
  CHECK_FALSE(find_ros_package(tree.root / "bad", why));
  CHECK(why.find("declares no <package><name>") != std::string::npos);
  Tree::make(tree.root / "broken/package.xml", "<package><name>x</package>");
  CHECK_FALSE(find_ros_package(tree.root / "broken", why));
  CHECK(why.find("cannot be read as XML") != std::string::npos);
  CHECK(package_tree(tree.referring) == fs::canonical(tree.robot));
  CHECK(is_package_name("robot_description"));
  CHECK_FALSE(is_package_name(""));
  CHECK_FALSE(is_package_name("a/b"));
  CHECK_FALSE(is_package_name(".."));
  CHECK_FALSE(is_package_name("a b"));
}

}  // namespace
}  // namespace bodyfmt::test
