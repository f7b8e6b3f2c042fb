// body2urdf: writes a URDF (plus mesh files) for a Choreonoid .body model.
// Exit codes (tools/common/front.h): 0 written with nothing lost; 1 written, with losses or
// other findings reported; 2 not written (bad usage, the model cannot be loaded, a fatal
// problem, or --strict losses).

#include "export_run.h"
#include "front.h"
#include "urdf_writer.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("body2urdf", "Export a Choreonoid .body model to URDF", {false, true});
  std::string output;
  std::string mesh_format = "stl";
  urdf::UrdfOptions options;
  CLI::App& app = front.app();
  app.add_option("-o,--output", output, "the URDF file to write ('-': standard output)")->required();
  app.add_option("--mesh-format", mesh_format, "format of written meshes")->check(CLI::IsMember({"stl", "dae"}));
  app.add_flag("--copy-meshes", options.copy_meshes,
               "copy external mesh files next to the URDF instead of referencing them");
  app.add_option("--package-uri", options.package_uri, "prefix mesh URIs with package://NAME/ (meshes are copied)");
  app.add_option("--mesh-folder", options.mesh_folder, "folder for meshes, relative to the URDF (inside its folder)")
      ->check(tools::check_inside_output_folder, "FOLDER");
  app.add_flag("--floating-base", options.floating_base,
               "add a 'world' link and a floating joint at the root's initial pose");
  app.add_flag("--devices-as-frames", options.devices_as_frames, "write devices as fixed child links");
  if (auto code = front.parse(argc, argv)) return *code;
  options.mesh_format = mesh_format == "dae" ? converters::MeshFormat::kDae : converters::MeshFormat::kStl;
  if (!options.package_uri.empty() && options.package_uri.back() != '/') options.package_uri += '/';

  return tools::run_export(
      front, output, [&](const Model& model, const Derived& derived, converters::OutputSet& out, DiagnosticSink& sink) {
        return urdf::write_urdf(model, derived, options, out, sink);
      });
}
