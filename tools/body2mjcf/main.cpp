// body2mjcf: writes an MJCF model (plus STL meshes) for MuJoCo 2.2.2 from a Choreonoid .body model.
// Exit codes (tools/common/front.h): 0 written with nothing lost; 1 written, with losses or
// other findings reported; 2 not written (bad usage, the model cannot be loaded, an inertia
// MuJoCo refuses or an asymmetric one without --balance-inertia, a fatal problem, or --strict
// losses and changed values).

#include "export_run.h"
#include "front.h"
#include "mjcf_writer.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>

#include <fmt/format.h>

#include <algorithm>

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("body2mjcf", "Export a Choreonoid .body model to MJCF (MuJoCo 2.2.2)", {false, true});
  std::string output;
  std::string actuators = "none";
  mjcf::MjcfOptions options;
  CLI::App& app = front.app();
  app.add_option("-o,--output", output, "the MJCF file to write ('-': standard output)")->required();
  app.add_flag("--balance-inertia", options.balance_inertia,
               "write the nearest valid inertia for links MuJoCo refuses, and the mean of each off-diagonal pair of "
               "an asymmetric one (a warning per link)");
  app.add_option("--actuators", actuators, "one actuator per revolute and prismatic joint")
      ->check(CLI::IsMember({"none", "position", "velocity"}));
  app.add_option("--mesh-folder", options.mesh_folder,
                 "folder for meshes, relative to the MJCF file (inside its folder; the compiler's meshdir)")
      ->check(tools::check_inside_output_folder, "FOLDER");
  CLI::Option* self_collision =
      app.add_flag("--self-collision", options.self_collision,
                   "let the model's bodies touch each other (MuJoCo's rule: a body and its parent never do); by "
                   "default none do, as in Choreonoid");
  app.add_option("--collision-group", options.collision_group,
                 fmt::format("keep the model's bodies apart with contact bit N (contype 2^N, conaffinity the other "
                             "bits) instead of <exclude> pairs: the export touches default geoms and exports of "
                             "other groups, not one of the same group (default: excludes up to {} colliding "
                             "bodies, else a group derived from the model name)",
                             mjcf::kMaxExcludeBodies))
      ->check(CLI::Range(1, mjcf::kMaxCollisionGroup))
      ->excludes(self_collision);
  if (auto code = front.parse(argc, argv)) return *code;
  options.actuators = actuators == "position"   ? mjcf::Actuators::kPosition
                      : actuators == "velocity" ? mjcf::Actuators::kVelocity
                                                : mjcf::Actuators::kNone;

  return tools::run_export(
      front, output,
      [&](const Model& model, const Derived& derived, converters::OutputSet& out, DiagnosticSink& sink) {
        return mjcf::write_mjcf(model, derived, options, out, sink);
      },
      [](const std::vector<Diagnostic>& diagnostics) {
        // A refused inertia has its own remedy.
        auto refused = [&diagnostics](auto is_rule) {
          return std::any_of(diagnostics.begin(), diagnostics.end(),
                             [&](const Diagnostic& d) { return d.severity >= Severity::kError && is_rule(d.rule_id); });
        };
        if (refused([](const std::string& id) { return id == "inertia-asymmetric"; }))
          return std::string(
              "MJCF holds a symmetric inertia (--balance-inertia writes the mean of each off-diagonal "
              "pair)");
        if (refused([](const std::string& id) { return id.rfind("inertia-", 0) == 0; }))
          return std::string("MuJoCo refuses an inertia (--balance-inertia writes the nearest valid one)");
        return std::string();
      });
}
