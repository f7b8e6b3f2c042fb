// bodyinfo: prints what a .body file contains, for people or as reference-comparable YAML.
// Exit codes (tools/common/front.h): 0 loaded cleanly, 1 findings at or above the fail level,
// 2 could not load or bad usage.

#include "bodyinfo_report.h"
#include "front.h"
#include "mass_report.h"
#include "number_options.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/pose.h>

#include <fmt/format.h>

#include <iostream>

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("bodyinfo", "Summarise a Choreonoid .body model", {});
  std::string format = "text";
  front.app()
      .add_option("--format", format,
                  "output format: text, or yaml in the layout of Choreonoid's reference values (json too with "
                  "--mass-from-geometry)")
      ->check(CLI::IsMember({"text", "yaml", "json"}));
  // Empty when the option is given without a value: then water's 1000 kg/m³.
  std::string density_text;
  CLI::Option* geometry_option =
      front.app()
          .add_option("--mass-from-geometry", density_text,
                      "print per link the written mass properties beside those computed from its collision shapes "
                      "(its visual ones where it has none) at DENSITY kg/m³ (default 1000), with its RigidBody "
                      "elements, and the tensor at the written mass")
          ->expected(0, 1)
          ->type_name("DENSITY")
          ->option_text("[=DENSITY]")
          ->check(tools::number_above_zero(false));
  std::string pose_text;
  CLI::Option* pose_option =
      front.app().add_option("--pose", pose_text,
                             "print every link's world frame at the joint positions NAME=VALUE,... (radians or "
                             "metres; '' is the zero pose) instead of the summary");
  if (auto code = front.parse(argc, argv)) return *code;
  const bool mass_from_geometry = geometry_option->count() > 0;
  const double density = density_text.empty() ? 1000.0 : std::strtod(density_text.c_str(), nullptr);
  if (format == "json" && !mass_from_geometry) {
    front.print_error("--format json is the form of --mass-from-geometry only");
    return tools::kExitFatal;
  }
  const auto [positions, pose_problems] = parse_joint_positions(pose_text);
  for (const std::string& problem : pose_problems) front.print_error("--pose: " + problem);
  if (!pose_problems.empty()) return tools::kExitFatal;

  CollectingSink collected;
  const std::string& path = front.inputs().front();
  auto policy = front.policy_for(path);
  if (!policy) return tools::kExitFatal;
  DiagnosticPolicy sink(collected, policy->options);
  std::optional<Model> model;
  Derived derived;
  std::vector<LinkBounds> choreonoid_boxes;
  std::vector<tools::LinkMassComparison> mass_comparison;
  if (auto input = front.open_input(path, sink)) {
    model = front.load(*input, sink);
    if (model) derived = compute_derived(*model, sink);
    if (model && mass_from_geometry) mass_comparison = tools::compare_mass_with_geometry(*model, density, sink);
    if (model && format == "yaml" && !mass_from_geometry) choreonoid_boxes = compute_choreonoid_bounds(*model, sink);
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
  if (pose_option->count() > 0) {
    const JointVector q = joint_vector(*model, positions);
    for (const std::string& problem : q.problems) front.print_error("--pose: " + problem);
    if (!q.problems.empty()) return tools::kExitFatal;
    std::cout << tools::format_pose_yaml(*model, compute_world_frames(*model, q.q));
  } else if (mass_from_geometry) {
    std::cout << tools::format_mass_comparison(*model, derived, density, mass_comparison, format);
  } else if (format == "yaml") {
    std::cout << tools::format_reference_yaml(*model, derived, choreonoid_boxes, diagnostics);
  } else {
    tools::write_summary(std::cout, *model, derived);
  }
  return tools::exit_code(diagnostics, policy->exit, false);
}
