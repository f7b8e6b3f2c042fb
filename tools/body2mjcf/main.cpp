// body2mjcf: writes an MJCF model (plus STL meshes) for MuJoCo 2.2.2 from a Choreonoid .body model.
// Exit codes (tools/common/front.h): 0 written with nothing lost; 1 written, with losses or
// other findings reported; 2 not written (bad usage, the model cannot be loaded, an inertia
// MuJoCo refuses without --balance-inertia, a fatal problem, or --strict losses).

#include "front.h"
#include "mjcf_writer.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>

#include <algorithm>
#include <filesystem>

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("body2mjcf", "Export a Choreonoid .body model to MJCF (MuJoCo 2.2.2)", {false, true});
  std::string output;
  std::string actuators = "none";
  mjcf::MjcfOptions options;
  CLI::App& app = front.app();
  app.add_option("-o,--output", output, "the MJCF file to write")->required();
  app.add_flag("--balance-inertia", options.balance_inertia,
               "write the nearest valid inertia for links MuJoCo refuses (a warning per link)");
  app.add_option("--actuators", actuators, "one actuator per revolute and prismatic joint")
      ->check(CLI::IsMember({"none", "position", "velocity"}));
  app.add_option("--mesh-folder", options.mesh_folder,
                 "folder for meshes, relative to the MJCF file (inside its folder; the compiler's meshdir)")
      ->check(
          [](const std::string& folder) -> std::string {
            const std::filesystem::path path(folder);
            bool inside = !folder.empty() && path.is_relative();
            for (const auto& part : path) inside = inside && part != "..";
            return inside ? std::string() : "the mesh folder must be a relative path inside the MJCF file's folder";
          },
          "FOLDER");
  if (auto code = front.parse(argc, argv)) return *code;
  options.actuators = actuators == "position"   ? mjcf::Actuators::kPosition
                      : actuators == "velocity" ? mjcf::Actuators::kVelocity
                                                : mjcf::Actuators::kNone;

  const std::string& path = front.inputs().front();
  auto policy = front.policy_for(path);
  if (!policy) return tools::kExitFatal;
  CollectingSink collected;
  DiagnosticPolicy sink(collected, policy->options);  // --strict: export-loss is an error
  bool written = false;
  if (auto input = front.open_input(path, sink)) {
    auto model = front.load(*input, sink);
    if (model && front.may_write(collected.diagnostics())) {
      const Derived derived = compute_derived(*model, sink);
      converters::OutputSet out(output);
      // --strict losses, a refused inertia and export errors stop the write.
      if (mjcf::write_mjcf(*model, derived, options, out, sink) && front.may_write(collected.diagnostics()))
        written = out.commit(sink);
    }
  }
  const bool refused_inertia = std::any_of(
      collected.diagnostics().begin(), collected.diagnostics().end(),
      [](const Diagnostic& d) { return d.severity >= Severity::kError && d.rule_id.rfind("inertia-", 0) == 0; });
  front.print(collected.diagnostics());
  if (!written)
    front.print_error(output + " was not written" +
                      (refused_inertia ? ": MuJoCo refuses an inertia (--balance-inertia writes the nearest valid one)"
                       : front.may_write(collected.diagnostics())
                           ? ""
                           : ": the model has errors (--best-effort writes it anyway)"));
  return tools::exit_code(collected.diagnostics(), policy->exit, !written);
}
