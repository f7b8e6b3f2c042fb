// bodyinfo: prints what a .body file contains, for people or as reference-comparable YAML.
// Exit codes (tools/common/front.h): 0 loaded cleanly, 1 findings at or above the fail level,
// 2 could not load or bad usage.

#include "bodyinfo_report.h"
#include "front.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/pose.h>

#include <fmt/format.h>

#include <iostream>

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("bodyinfo", "Summarise a Choreonoid .body model", {});
  std::string format = "text";
  front.app()
      .add_option("--format", format, "output format: text, or yaml in the layout of Choreonoid's reference values")
      ->check(CLI::IsMember({"text", "yaml"}));
  std::string pose_text;
  CLI::Option* pose_option =
      front.app().add_option("--pose", pose_text,
                             "print every link's world frame at the joint positions NAME=VALUE,... (radians or "
                             "metres; '' is the zero pose) instead of the summary");
  if (auto code = front.parse(argc, argv)) return *code;
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
  if (pose_option->count() > 0) {
    const JointVector q = joint_vector(*model, positions);
    for (const std::string& problem : q.problems) front.print_error("--pose: " + problem);
    if (!q.problems.empty()) return tools::kExitFatal;
    std::cout << tools::format_pose_yaml(*model, compute_world_frames(*model, q.q));
  } else if (format == "yaml") {
    std::cout << tools::format_reference_yaml(*model, derived, choreonoid_boxes, diagnostics);
  } else {
    tools::write_summary(std::cout, *model, derived);
  }
  return tools::exit_code(diagnostics, policy->exit, false);
}
