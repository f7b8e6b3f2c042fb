// body2urdf: writes a URDF (plus mesh files) for a Choreonoid .body model.
// Exit codes: 0 written with nothing lost; 1 written with losses (or other findings) reported;
// 2 not written (bad usage, the model cannot be loaded, a fatal problem, or --strict losses).

#include <bodyfmt/diagnostic_policy.h>
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include "urdf_writer.h"

#include <CLI/CLI.hpp>

#include <iostream>

namespace {
bool is_export_rule(const bodyfmt::Diagnostic& d) { return d.rule_id.rfind("export-", 0) == 0; }
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Export a Choreonoid .body model to URDF"};
  std::string input, output;
  std::string mesh_format = "stl";
  bodyfmt::urdf::UrdfOptions options;
  bool strict = false;
  bool quiet = false;
  std::vector<std::string> package_paths;
  app.add_option("file", input, "the .body file")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output", output, "the URDF file to write")->required();
  app.add_option("--mesh-format", mesh_format, "format of written meshes")->check(CLI::IsMember({"stl", "dae"}));
  app.add_flag("--copy-meshes", options.copy_meshes, "copy external mesh files next to the URDF instead of referencing them");
  app.add_option("--package-uri", options.package_uri, "prefix mesh URIs with package://NAME/ (meshes are copied)");
  app.add_option("--mesh-folder", options.mesh_folder, "folder for meshes, relative to the URDF");
  app.add_flag("--floating-base", options.floating_base, "add a 'world' link and a floating joint at the root's initial pose");
  app.add_flag("--devices-as-frames", options.devices_as_frames, "write devices as fixed child links");
  app.add_flag("--strict", strict, "treat every export loss as an error: nothing is written");
  app.add_flag("-q,--quiet", quiet, "print no notes");
  app.add_option("--package-path", package_paths, "a folder holding ROS packages for package:// URIs (repeatable)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  options.mesh_format = mesh_format == "dae" ? bodyfmt::converters::MeshFormat::kDae : bodyfmt::converters::MeshFormat::kStl;
  if (!options.package_uri.empty() && options.package_uri.back() != '/') options.package_uri += '/';

  bodyfmt::LoadOptions load_options;
  load_options.package_paths = package_paths;
  bodyfmt::CollectingSink collected;
  bodyfmt::PolicyOptions policy_options;
  policy_options.strict = strict;  // export-loss becomes an error, so nothing is written
  bodyfmt::DiagnosticPolicy sink(collected, policy_options);
  auto model = bodyfmt::load_body(input, load_options, sink);
  bool written = false;
  if (model && collected.count(bodyfmt::Severity::kFatal) == 0) {
    const bodyfmt::Derived derived = bodyfmt::compute_derived(*model, sink);
    bodyfmt::converters::OutputSet out(output);
    const bool ok = bodyfmt::urdf::write_urdf(*model, derived, options, out, sink);
    // Export errors (--strict losses) stop the write; loader errors are listed but, as
    // bodyinfo does, the model that did load is still exported.
    bool export_errors = false;
    for (const auto& d : collected.diagnostics()) {
      export_errors = export_errors || (d.severity >= bodyfmt::Severity::kError && is_export_rule(d));
    }
    if (ok && !export_errors) written = out.commit(sink);
  }

  auto diagnostics = collected.diagnostics();
  bodyfmt::sort_diagnostics(diagnostics);
  for (const auto& d : diagnostics) {
    if (d.severity == bodyfmt::Severity::kNote && quiet) continue;
    std::cerr << bodyfmt::format_diagnostic(d) << '\n';
  }
  if (!written) {
    std::cerr << "body2urdf: " << output << " was not written\n";
    return 2;
  }
  for (const auto& d : diagnostics) {
    if (is_export_rule(d) && d.severity >= bodyfmt::Severity::kWarning) return 1;
  }
  return 0;
}
