// bodyinfo: prints what a .body file contains, for people or as reference-comparable YAML.
// Exit codes: 0 loaded without errors, 1 loaded with errors, 2 could not load or bad usage.

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include "bodyinfo_report.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"Summarise a Choreonoid .body model"};
  std::string path;
  std::string format = "text";
  std::size_t max_nodes = bodyfmt::LoadOptions{}.max_expanded_yaml_nodes;
  bool quiet = false;
  bool no_meshes = false;
  std::vector<std::string> package_paths;
  app.add_option("file", path, "the .body file")->required();
  app.add_option("--format", format, "output format")->check(CLI::IsMember({"text", "yaml"}));
  app.add_option("--max-yaml-nodes", max_nodes, "limit on YAML nodes after alias expansion");
  app.add_flag("-q,--quiet", quiet, "print no notes");
  app.add_flag("--no-meshes", no_meshes, "do not import external mesh files");
  app.add_option("--package-path", package_paths, "a folder holding ROS packages for package:// URIs (repeatable)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  bodyfmt::LoadOptions options;
  options.max_expanded_yaml_nodes = max_nodes;
  options.load_meshes = !no_meshes;
  options.package_paths = package_paths;
  bodyfmt::CollectingSink sink;
  auto model = bodyfmt::load_body(path, options, sink);
  bodyfmt::Derived derived;
  if (model) derived = bodyfmt::compute_derived(*model, sink);

  auto diagnostics = sink.diagnostics();
  bodyfmt::sort_diagnostics(diagnostics);
  for (const auto& d : diagnostics) {
    if (d.severity == bodyfmt::Severity::kNote && (quiet || format == "yaml")) continue;
    std::cerr << bodyfmt::format_diagnostic(d) << '\n';
  }
  if (!model) {
    if (format == "yaml") std::cout << "loaded: false\n";
    return 2;
  }
  if (format == "yaml") {
    bodyfmt::CollectingSink ignored;  // the same meshes again: already reported above
    const auto boxes = bodyfmt::compute_choreonoid_bounds(*model, ignored);
    std::cout << bodyfmt::info::format_reference_yaml(*model, derived, boxes, diagnostics);
  }
  else std::cout << bodyfmt::info::format_summary(*model, derived);
  return sink.error_count() > 0 ? 1 : 0;
}
