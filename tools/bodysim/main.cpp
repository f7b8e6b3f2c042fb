// bodysim: the Simbody dynamics checker (dynamics/README.md). One command line with three
// CLI11 subcommands, each with the front's options (tools/common/front.h) and its own:
//   bodysim check-tank MODEL [--balance-inertia]    the tank suite; one line per check
//   bodysim check MODEL [--balance-inertia]         generic checks for any model
//   bodysim run MODEL --scenario S.yaml --csv out.csv
// Exit codes (tools/common/front.h): 0 every check passed (run: the CSV was written); 1 a check
// failed or findings at the fail level; 2 usage, I/O, a model that cannot be simulated
// (an unphysical inertia without --balance-inertia, not a tank for check-tank) or a fatal error.
// main keeps the options and picks the subcommand; model_screening refuses a model no engine
// should see (simbody_contact_shapes: what --contact simbody takes), check_commands and
// scenario_command run the subcommands, check_report prints, run_diagnostics ends the run.

#include "check_commands.h"
#include "front.h"
#include "model_screening.h"
#include "number_options.h"
#include "run_diagnostics.h"
#include "scenario_command.h"
#include "sim_command.h"

#include <bodyfmt/dynamics/checks.h>
#include <bodyfmt/dynamics/scenario.h>
#include <bodyfmt/rules.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>

namespace {

using namespace bodyfmt;

const CLI::Validator kPositive = tools::number_above_zero(false), kNonNegative = tools::number_above_zero(true);

/// The options every subcommand takes besides the front's: the simulation's.
void add_simulation_options(CLI::App& app, dynamics::SimOptions& sim, std::size_t& max_links) {
  app.add_flag("--balance-inertia", sim.balance_inertia,
               "simulate links with an unphysical inertia with the nearest valid one, an asymmetric one symmetrised (a "
               "warning per link)");
  app.add_option("--accuracy", sim.accuracy, "Runge-Kutta-Merson accuracy (default 1e-5)")
      ->check(tools::finite_number_in(1e-12, 1e-1));
  app.add_option("--contact", sim.contact_model,
                 "floor contact: points (collision-shape vertices, the default) or simbody (Simbody's compliant "
                 "contact: Bricks and elastic-foundation meshes against a half-space)")
      ->transform(CLI::Validator(
          [](std::string& value) {
            // The names are all a user sees, in --help and in errors, never the enum's
            // numbers (issue 40); CLI11 converts the number the name is replaced by.
            static const std::map<std::string, dynamics::ContactModel> kModels = {
                {"points", dynamics::ContactModel::kPoints}, {"simbody", dynamics::ContactModel::kSimbody}};
            const auto model = kModels.find(value);
            if (model == kModels.end()) return "must be points or simbody, not " + value;
            value = std::to_string(static_cast<int>(model->second));
            return std::string();
          },
          "{points,simbody}"))
      ->type_name("TEXT");
  app.add_option("--friction", sim.contact_params.friction, "Coulomb friction with the floor (default 0.5)")
      ->check(tools::finite_number_in(0.0, 10.0));
  app.add_option("--contact-depth", sim.contact_params.reference_depth,
                 "contact stiffness: the depth the model's weight on four points sinks (m, default 1e-4)")
      ->check(tools::finite_number_in(1e-7, 1e-1));
  app.add_option("--transition-velocity", sim.contact_params.transition_velocity,
                 "slip speed at which friction reaches μ (m/s, default 0.05)")
      ->check(tools::finite_number_in(1e-5, 1.0));
  app.add_option("--max-steps-per-second", sim.max_steps_per_second,
                 "stop a simulation whose integrator takes more steps per simulated second (default 50000; 0: no "
                 "limit)")
      ->check(kNonNegative);
  app.add_option("--max-cpu", sim.max_cpu_seconds, "stop after this many CPU seconds (default 300; 0: no limit)")
      ->check(kNonNegative);
  app.add_option("--max-links", max_links,
                 "refuse models with more links (default 200; integration time grows faster than the link count)")
      ->check(kPositive);
}

}  // namespace

int main(int argc, char** argv) {
  const char* const kSubcommands[] = {"check-tank", "check", "run"};
  CLI::App cli("bodysim: the Simbody dynamics checker for Choreonoid .body models", "bodysim");
  cli.set_version_flag("--version", std::string("bodysim ") + BODYFMT_VERSION, "print the version and exit");
  cli.require_subcommand(1);
  tools::SimCommand command;
  dynamics::TankSuiteOptions& suite = command.suite;
  dynamics::SimOptions& sim = suite.sim;
  std::map<std::string, std::unique_ptr<tools::Front>> fronts;
  auto subcommand = [&](const std::string& name, const std::string& description) -> CLI::App& {
    CLI::App& app = *cli.add_subcommand(name, description);
    fronts[name] = std::make_unique<tools::Front>("bodysim " + name, app, tools::Front::Features{false, false});
    add_simulation_options(app, sim, command.max_links);
    return app;
  };
  CLI::App& check_tank = subcommand("check-tank",
                                    "Run the tracked-vehicle dynamics suite (Simbody) on a model with two "
                                    "pseudo_continuous_track links");
  check_tank
      .add_option("--cross-check", command.cross_check,
                  "also run the drive, spin and turret scenarios in MuJoCo 2.2.2 on body2mjcf's export")
      ->check(CLI::IsMember({"mujoco"}));
  check_tank.add_option("--p-gain", suite.p_gain, "turret servo P gain, N·m/rad (default 200)")->check(kPositive);
  check_tank.add_option("--d-gain", suite.d_gain, "turret servo D gain, N·m·s/rad (default 50)")->check(kNonNegative);
  CLI::App& check = subcommand("check", "Run the generic dynamics checks (Simbody) on any model");
  check
      .add_option("--cross-check", command.cross_check,
                  "also run the locked-joint drop in MuJoCo 2.2.2 on body2mjcf's export (a free root only)")
      ->check(CLI::IsMember({"mujoco"}));
  CLI::App& run = subcommand("run", "Run a scenario and write trajectories as CSV (Simbody)");
  run.add_option("--scenario", command.scenario_path, "the scenario file (YAML; see dynamics/README.md)")->required();
  run.add_option("--csv", command.csv_path, "the CSV file to write")->required();
  run.add_option("--max-duration", command.limits.max_duration,
                 "refuse scenarios that simulate longer (s, default 600)")
      ->check(kPositive);
  run.add_option("--max-rows", command.limits.max_rows, "refuse scenarios with more CSV rows (default 1000000)")
      ->check(kPositive);
  run.add_option("--max-commands", command.limits.max_commands, "refuse scenarios with more commands (default 100000)")
      ->check(kPositive);

  cli.footer("Run `bodysim SUBCOMMAND --help` for the options of a subcommand.");  // after them: not inherited

  if (argc < 2) {
    std::cerr << "bodysim: error: a subcommand is required (check-tank, check or run)\n" << cli.help();
    return tools::kExitFatal;
  }
  // CLI11 would call an unknown subcommand an unexpected argument: name it as what it is.
  if (argv[1][0] != '-' && std::none_of(std::begin(kSubcommands), std::end(kSubcommands),
                                        [&](const char* name) { return std::strcmp(argv[1], name) == 0; })) {
    std::cerr << "bodysim: error: unknown subcommand \"" << argv[1]
              << "\" (check-tank, check or run)\nRun with --help for more information.\n";
    return tools::kExitFatal;
  }
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e) == 0 ? tools::kExitClean : tools::kExitFatal;
  }
  for (const char* name : kSubcommands)
    if (cli.got_subcommand(name)) command.name = name;
  tools::Front& front = *fronts.at(command.name);
  front.parsed();

  const std::string& path = front.inputs().front();
  auto policy = front.policy_for(path);
  if (!policy) return tools::kExitFatal;
  tools::RunDiagnostics diagnostics(front, *policy);
  std::optional<Model> model;
  if (auto input = front.open_input(path, diagnostics.sink())) model = front.load(*input, diagnostics.sink());
  if (!model) return diagnostics.finish(true, "");
  const tools::Screening screening = tools::screen_model(*model, command, diagnostics);
  if (!screening.derived) return diagnostics.finish(true, screening.refusal);

  const std::string& csv_path = command.csv_path;
  try {
    if (command.name == "run") return tools::run_scenario_command(command, *model, *screening.derived, diagnostics);
    return tools::run_check_command(command, path, *model, *screening.derived, diagnostics);
  } catch (const dynamics::EngineFailure& e) {
    report_rule(diagnostics.sink(), "dynamics-engine-failure", e.where, e.what());
    return diagnostics.finish(
        true, "the simulation failed" + std::string(command.name == "run" ? "; " + csv_path + " was not written" : ""));
  } catch (const dynamics::WorkBudgetExceeded& e) {
    report_rule(diagnostics.sink(), "dynamics-work-budget", e.where, e.what());
    return diagnostics.finish(true, "the simulation was stopped" +
                                        std::string(command.name == "run" ? "; " + csv_path + " was not written" : ""));
  } catch (const std::exception& e) {
    return diagnostics.finish(true, std::string("the simulation failed: ") + e.what());
  }
}
