// bodyinfo: prints what a .body file contains, for people or as reference-comparable YAML.
// Exit codes (tools/common/front.h): 0 loaded cleanly, 1 findings at or above the fail level,
// 2 could not load or bad usage.

#include "bodyinfo_report.h"
#include "front.h"

#include <bodyfmt/derived.h>

#include <iostream>

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("bodyinfo", "Summarise a Choreonoid .body model", {});
  std::string format = "text";
  front.app()
      .add_option("--format", format, "output format: text, or yaml in the layout of Choreonoid's reference values")
      ->check(CLI::IsMember({"text", "yaml"}));
  if (auto code = front.parse(argc, argv)) return *code;

  CollectingSink collected;
  const std::string& path = front.inputs().front();
  auto policy = front.policy_for(path);
  if (!policy) return tools::kExitFatal;
  DiagnosticPolicy sink(collected, policy->options);
  std::optional<Model> model;
  Derived derived;
  std::vector<LinkBounds> choreonoid_boxes;
  if (auto input = front.open_input(path, sink)) {
    model = front.load(*input, sink);
    if (model) derived = compute_derived(*model, sink);
    if (model && format == "yaml") choreonoid_boxes = compute_choreonoid_bounds(*model, sink);
  }

  std::vector<Diagnostic> diagnostics = collected.diagnostics();
  sort_diagnostics(diagnostics);
  // The YAML form is compared with reference files: notes would only be noise there.
  std::vector<Diagnostic> printed;
  for (const Diagnostic& d : diagnostics)
    if (!(d.severity == Severity::kNote && format == "yaml")) printed.push_back(d);
  front.print(printed);
  if (!model) {
    if (format == "yaml") std::cout << "loaded: false\n";
    return tools::kExitFatal;
  }
  if (format == "yaml") {
    std::cout << tools::format_reference_yaml(*model, derived, choreonoid_boxes, diagnostics);
  } else {
    tools::write_summary(std::cout, *model, derived);
  }
  return tools::exit_code(diagnostics, policy->exit, false);
}
