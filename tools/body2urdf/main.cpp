// body2urdf: writes a URDF (plus mesh files) for a Choreonoid .body model.
// Exit codes (tools/common/front.h): 0 written with nothing lost; 1 written, with losses or
// other findings reported; 2 not written (bad usage, the model cannot be loaded, a fatal
// problem, an asymmetric inertia without --balance-inertia, or --strict losses and changed values).

#include "export_run.h"
#include "front.h"
#include "urdf_writer.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/package_map.h>

#include <filesystem>

namespace {

namespace fs = std::filesystem;

/// "package://NAME" or "package://NAME/": NAME, else empty.
std::string package_name(const std::string& uri) {
  if (!bodyfmt::is_package_uri(uri)) return {};
  std::string name = uri.substr(std::string_view("package://").size());
  if (!name.empty() && name.back() == '/') name.pop_back();
  return bodyfmt::is_package_name(name) ? name : std::string();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("body2urdf", "Export a Choreonoid .body model to URDF", {false, true});
  std::string output;
  std::string mesh_format = "stl";
  urdf::UrdfOptions options;
  CLI::App& app = front.app();
  app.add_option("-o,--output", output, "the URDF file to write ('-': standard output)")->required();
  app.add_option("--mesh-format", mesh_format, "format of written and copied meshes")
      ->check(CLI::IsMember({"stl", "dae"}));
  bool reference_meshes = false;
  app.add_flag("--copy-meshes", options.copy_meshes,
               "copy external mesh files next to the URDF (converted to --mesh-format), even inside a ROS package");
  app.add_flag("--reference-meshes", reference_meshes,
               "refer to external mesh files where they are, by paths relative to the URDF (not portable)")
      ->excludes("--copy-meshes");
  app.add_option("--package-uri", options.package_uri,
                 "package://NAME: mesh URIs relative to the ROS package that holds the URDF (the nearest "
                 "package.xml above it); meshes are copied")
      ->check(
          [](const std::string& value) {
            return package_name(value).empty() ? std::string("must be package://NAME (a ROS package name)")
                                               : std::string();
          },
          "package://NAME")
      ->excludes("--reference-meshes");
  app.add_option("--mesh-folder", options.mesh_folder,
                 "folder for meshes, relative to the URDF: inside its folder, or anywhere inside the ROS package "
                 "with --package-uri (default meshes/STEM)");
  app.add_flag("--mujoco,!--no-mujoco", options.mujoco_compiler,
               "write <mujoco><compiler strippath=\"false\"/></mujoco> so that MuJoCo finds meshes in folders "
               "(default on)");
  app.add_flag("--floating-base", options.floating_base,
               "add a 'world' link and a floating joint at the root's initial pose (a fixed root always gets a "
               "fixed one)");
  app.add_flag("--capsules", options.capsules,
               "write capsules as <capsule> (Drake and sdformat read it, urdfdom refuses it; default: a mesh)");
  app.add_flag("--devices-as-frames", options.devices_as_frames, "write devices as fixed child links");
  app.add_flag("--balance-inertia", options.balance_inertia,
               "write the nearest valid inertia for links whose inertia Drake, gz-math and MuJoCo refuse, and the mean "
               "of each off-diagonal pair of an asymmetric one (a warning per link; the tensors body2mjcf writes)");
  if (auto code = front.parse(argc, argv)) return *code;
  options.mesh_format = mesh_format == "dae" ? converters::MeshFormat::kDae : converters::MeshFormat::kStl;

  std::error_code ec;
  const fs::path given_dir = output == "-" ? fs::path(".") : fs::path(output).parent_path();
  const fs::path out_dir = fs::absolute(given_dir.empty() ? fs::path(".") : given_dir, ec).lexically_normal();
  std::optional<RosPackage> package;
  if (!options.package_uri.empty()) {
    const std::string name = package_name(options.package_uri);
    std::string why;
    package = find_ros_package(out_dir, why);
    if (!package) {
      front.print_error("--package-uri needs the URDF inside a ROS package: " + why);
      return tools::kExitFatal;
    }
    if (package->name != name) {
      front.print_error("--package-uri names the package '" + name + "', but " +
                        (package->root / "package.xml").string() + " declares '" + package->name + "'");
      return tools::kExitFatal;
    }
    options.package_uri = "package://" + name + "/";
    options.package_root = package->root;
  }
  // The default is a URDF that resolves on another machine: package:// URIs inside the ROS
  // package that holds it, else every mesh copied beside it (as MJCF and glTF are written).
  if (!options.copy_meshes && !reference_meshes && !package) {
    std::string why;
    package = find_ros_package(out_dir, why);
    if (package && package_name("package://" + package->name).empty()) package.reset();
    if (package) {
      options.package_uri = "package://" + package->name + "/";
      options.package_root = package->root;
    } else {
      options.copy_meshes = true;
    }
  }
  if (!options.mesh_folder.empty()) {
    std::string why = tools::check_inside_output_folder(options.mesh_folder);
    if (!why.empty() && package && fs::path(options.mesh_folder).is_relative() &&
        path_in_package(package->root, out_dir / options.mesh_folder))
      why.clear();
    if (!why.empty()) {
      front.print_error("--mesh-folder " + options.mesh_folder + ": " + why +
                        (package ? " (or inside the ROS package " + package->root.string() + ")" : ""));
      return tools::kExitFatal;
    }
  }

  return tools::run_export(
      front, output, [&](const Model& model, const Derived& derived, converters::OutputSet& out, DiagnosticSink& sink) {
        if (package) out.allow_root(package->root);
        return urdf::write_urdf(model, derived, options, out, sink);
      });
}
