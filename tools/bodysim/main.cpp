// bodysim: the Simbody dynamics checker (dynamics/README.md). One command line with three
// CLI11 subcommands, each with the front's options (tools/common/front.h) and its own:
//   bodysim check-tank MODEL [--balance-inertia]    the tank suite; one line per check
//   bodysim check MODEL [--balance-inertia]         generic checks for any model
//   bodysim run MODEL --scenario S.yaml --csv out.csv
// Exit codes (tools/common/front.h): 0 every check passed (run: the CSV was written); 1 a check
// failed or findings at the fail level; 2 usage, I/O, a model that cannot be simulated
// (an unphysical inertia without --balance-inertia, not a tank for check-tank) or a fatal error.

#include "front.h"
#include "number_options.h"
#include "output_guard.h"
#include "report_lines.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/converters/protect_inputs.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/dynamics/checks.h>
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
#include <bodyfmt/dynamics/drop_cross_check.h>
#endif
#include <bodyfmt/dynamics/scenario.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/validate.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>

namespace {

using namespace bodyfmt;

/// bodycheck's rules under bodysim's policy, except the inertia findings that Simulation::build
/// reports itself with what it does about them (refused, or balanced with --balance-inertia).
/// An asymmetric tensor is simulated symmetrised (Simulation and body2mjcf's writer take
/// (I + Iᵀ)/2, the mean of each off-diagonal pair): with --balance-inertia that is a balance
/// like the others, said at the tensor's line; without it, bodycheck's error.
class ValidatorFirst : public DiagnosticSink {
 public:
  ValidatorFirst(DiagnosticSink& inner, bool balance) : inner_(inner), balance_(balance) {}
  void report(Diagnostic d) override {
    if (d.rule_id == "inertia-triangle" || d.rule_id == "inertia-not-positive-definite") {
      held_.push_back(std::move(d));
      return;
    }
    if (balance_ && d.rule_id == "inertia-asymmetric") {
      report_rule(inner_, "dynamics-inertia-balanced", d.location,
                  d.message +
                      "; simulated with --balance-inertia as the symmetrised tensor, the mean of each "
                      "off-diagonal pair (Choreonoid uses the 9 numbers as given)",
                  "write the 6-element form [Ixx, Ixy, Ixz, Iyy, Iyz, Izz] with the values you mean");
      return;
    }
    inner_.report(std::move(d));
  }
  /// When another error stops the run before Simulation::build, the inertia findings it would
  /// have reported are bodycheck's: every finding is said before bodysim refuses, as bodycheck
  /// says them on the file. (With --balance-inertia they are not errors of this run.)
  void release_held() {
    if (!balance_)
      for (Diagnostic& d : held_) inner_.report(std::move(d));
    held_.clear();
  }

 private:
  DiagnosticSink& inner_;
  bool balance_;
  std::vector<Diagnostic> held_;
};

std::string number(double v) { return fmt::format("{:.6g}", v); }

/// The model's checks, then the build's self-test apart, then the counts.
void print_results(const std::vector<dynamics::CheckResult>& results) {
  int self_tests = 0;
  for (const auto& r : results) self_tests += r.self_test ? 1 : 0;
  if (self_tests > 0) {
    std::cout << "self-test of the Simbody build (its system against the derived data it was built from):\n";
    for (const auto& r : results)
      if (r.self_test) std::cout << tools::check_lines(r);
    std::cout << "checks of the model:\n";
  }
  int passed = 0, failed = 0, skipped = 0;
  for (const auto& r : results) {
    if (!r.self_test) std::cout << tools::check_lines(r);
    (r.skipped ? skipped : r.passed ? passed : failed) += 1;
  }
  std::cout << fmt::format("{} of {} checks passed, {} failed, {} skipped\n", passed, passed + failed, failed, skipped);
}

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
  // Only one subcommand runs, so they share the variables their options set.
  dynamics::TankSuiteOptions suite;
  dynamics::SimOptions& sim = suite.sim;
  std::string scenario_path, csv_path, cross_check;
  std::size_t max_links = 200;
  dynamics::ScenarioLimits limits;
  std::map<std::string, std::unique_ptr<tools::Front>> fronts;
  auto subcommand = [&](const std::string& name, const std::string& description) -> CLI::App& {
    CLI::App& app = *cli.add_subcommand(name, description);
    fronts[name] = std::make_unique<tools::Front>("bodysim " + name, app, tools::Front::Features{false, false});
    add_simulation_options(app, sim, max_links);
    return app;
  };
  CLI::App& check_tank = subcommand("check-tank",
                                    "Run the tracked-vehicle dynamics suite (Simbody) on a model with two "
                                    "pseudo_continuous_track links");
  check_tank
      .add_option("--cross-check", cross_check,
                  "also run the drive, spin and turret scenarios in MuJoCo 2.2.2 on body2mjcf's export")
      ->check(CLI::IsMember({"mujoco"}));
  check_tank.add_option("--p-gain", suite.p_gain, "turret servo P gain, N·m/rad (default 200)")->check(kPositive);
  check_tank.add_option("--d-gain", suite.d_gain, "turret servo D gain, N·m·s/rad (default 50)")->check(kNonNegative);
  CLI::App& check = subcommand("check", "Run the generic dynamics checks (Simbody) on any model");
  check
      .add_option("--cross-check", cross_check,
                  "also run the locked-joint drop in MuJoCo 2.2.2 on body2mjcf's export (a free root only)")
      ->check(CLI::IsMember({"mujoco"}));
  CLI::App& run = subcommand("run", "Run a scenario and write trajectories as CSV (Simbody)");
  run.add_option("--scenario", scenario_path, "the scenario file (YAML; see dynamics/README.md)")->required();
  run.add_option("--csv", csv_path, "the CSV file to write")->required();
  run.add_option("--max-duration", limits.max_duration, "refuse scenarios that simulate longer (s, default 600)")
      ->check(kPositive);
  run.add_option("--max-rows", limits.max_rows, "refuse scenarios with more CSV rows (default 1000000)")
      ->check(kPositive);
  run.add_option("--max-commands", limits.max_commands, "refuse scenarios with more commands (default 100000)")
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
  std::string command;
  for (const char* name : kSubcommands)
    if (cli.got_subcommand(name)) command = name;
  tools::Front& front = *fronts.at(command);
  front.parsed();

  const std::string& path = front.inputs().front();
  auto policy = front.policy_for(path);
  if (!policy) return tools::kExitFatal;
  CollectingSink collected;
  DiagnosticPolicy sink(collected, policy->options);
  std::optional<Model> model;
  if (auto input = front.open_input(path, sink)) model = front.load(*input, sink);
  auto finish = [&](bool fatal, const std::string& why) {
    front.print(collected.diagnostics());
    // The reason ends the run, with the first error that stopped it: after a hundred warnings
    // (legacy keys, say) "see above" would point nowhere.
    if (why.find("nothing was simulated") != std::string::npos)
      std::cerr << tools::nothing_simulated(front.tool_name(), why, collected.diagnostics());
    else if (!why.empty())
      front.print_error(why);
    return tools::exit_code(collected.diagnostics(), policy->exit, fatal);
  };
  if (!model) return finish(true, "");
  if (collected.error_count() > 0) return finish(true, "the model has errors; nothing was simulated");
  if (model->links.size() > max_links) {
    const Link& first_over = model->links[max_links];
    report_rule(sink, "dynamics-model-size", source_of(first_over, LinkSources::kName),
                fmt::format("the model has {} links, more than bodysim simulates (--max-links {}); this is link {}, "
                            "the first over the limit",
                            model->links.size(), max_links, max_links + 1),
                "raise --max-links to simulate it anyway; 100 links take seconds, 300 links about half a minute");
    return finish(true, "the model is too large to simulate; nothing was simulated");
  }
  const Derived derived = compute_derived(*model, sink);
  // The validator first: what bodycheck calls an error (a reversed range, a moving massless
  // link, ...) is refused at its line before any engine sees it.
  {
    ValidatorFirst validator(sink, sim.balance_inertia);
    validate::check_model(*model, derived, {}, validator);
    if (collected.error_count() > 0) validator.release_held();
  }
  if (collected.error_count() > 0)
    return finish(true, "the model has errors (bodycheck's rules); nothing was simulated");
  if (sim.contact_model == dynamics::ContactModel::kSimbody) {
    // Simbody's elastic-foundation meshes did not finish 1 simulated second of SimpleTank (its
    // Extrusion tracks) in 10 CPU minutes: until that is understood, --contact simbody takes
    // Box collision shapes (Bricks) only, rather than hang.
    for (const Link& link : model->links)
      for (const Shape& shape : link.shapes)
        if (shape.collision && !std::holds_alternative<Box>(shape.geometry)) {
          report_rule(sink, "dynamics-contact-geometry", shape.source,
                      fmt::format("--contact simbody takes Box collision shapes only (as Bricks); this {} of link "
                                  "\"{}\" would be an elastic-foundation mesh, which does not finish in "
                                  "reasonable time",
                                  geometry_type_name(shape.geometry), link.name),
                      "use the default --contact points");
          return finish(true, "--contact simbody cannot simulate this model; nothing was simulated");
        }
  }

  std::string why;
  try {
    if (command == "run") {
      // Refused before the simulation rather than after it (OutputSet refuses it again).
      std::vector<InputFile> inputs = input_files(*model);
      inputs.push_back({scenario_path, "the scenario"});
      const std::string clash = tools::input_clash(csv_path, inputs);
      if (!clash.empty()) {
        report_rule(sink, "export-write", SourceLocation{csv_path, 0, 0},
                    fmt::format("cannot write '{}': {}; nothing was written", csv_path, clash));
        return finish(true, csv_path + " was not written");
      }
      std::optional<dynamics::ScenarioSpec> scenario = dynamics::read_scenario(scenario_path, *model, sink);
      if (!scenario) return finish(true, "the scenario cannot be read; nothing was simulated");
      limits.max_steps_per_second = sim.max_steps_per_second;
      if (!dynamics::check_scenario(*scenario, limits, sink))
        return finish(true, "the scenario is refused; nothing was simulated");
      std::ostringstream csv;
      dynamics::RunStats stats;
      if (!dynamics::run_scenario(*model, derived, *scenario, sim, csv, sink, &stats))
        return finish(true, csv_path + " was not written");
      converters::OutputSet out(csv_path);
      converters::protect_inputs(out, *model);
      out.protect(scenario_path, "the scenario");
      out.set_main(csv.str());
      if (!out.commit(sink)) return finish(true, csv_path + " was not written");
      // With the table on standard output (-o -), the summary goes beside the diagnostics.
      (out.to_stdout() ? std::cerr : std::cout) << fmt::format(
          "bodysim run: {} s of {} simulated in {} Runge-Kutta-Merson steps, {} force evaluations "
          "(accuracy {:g}); wrote {}\n",
          number(scenario->duration), model->name, stats.steps, stats.evaluations, sim.accuracy, csv_path);
      return finish(false, "");
    }
    std::vector<dynamics::CheckResult> results;
    dynamics::TankLayout tank;
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
    dynamics::DropCrossCheckReport drop_report;
#endif
    if (command == "check-tank") {
      results = dynamics::run_tank_suite(*model, derived, suite, sink, why, &tank);
      if (!results.empty() && !cross_check.empty()) {
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
        std::vector<dynamics::CheckResult> cross = dynamics::run_mujoco_cross_check(*model, derived, suite, sink, why);
        if (cross.empty()) return finish(true, why.empty() ? "the MuJoCo cross-check failed" : why);
        results.insert(results.end(), cross.begin(), cross.end());
#else
        return finish(true, "this bodysim was built without MuJoCo: --cross-check mujoco is unavailable");
#endif
      }
    } else {
      results = dynamics::run_generic_checks(*model, derived, sim, sink, why);
      if (!results.empty() && !cross_check.empty()) {
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
        dynamics::DropCrossCheckOptions drop;
        drop.sim = sim;
        std::vector<dynamics::CheckResult> cross =
            dynamics::run_drop_cross_check(*model, derived, drop, sink, why, &drop_report);
        if (cross.empty()) return finish(true, why.empty() ? "the MuJoCo cross-check failed" : why);
        results.insert(results.end(), cross.begin(), cross.end());
#else
        return finish(true, "this bodysim was built without MuJoCo: --cross-check mujoco is unavailable");
#endif
      }
    }
    if (results.empty()) return finish(true, why.empty() ? "nothing was simulated" : why + "; nothing was simulated");
    std::cout << tools::wrap(
        fmt::format("bodysim {}: {} ({}), total mass {} kg", command, model->name, path, number(derived.total_mass)),
        2);
    std::cout << tools::wrap(
        fmt::format(
            "  Simbody 3.7, Runge-Kutta-Merson accuracy {:g}; floor contact {}, friction {:g}, "
            "dissipation {:g} s/m, transition {:g} m/s; joint ranges enforced by stops ({:g} per rad or m{})",
            sim.accuracy,
            sim.contact_model == dynamics::ContactModel::kSimbody
                ? "by Simbody's CompliantContactSubsystem (HalfSpace floor; Box shapes as Bricks, other shapes as "
                  "elastic-foundation triangle meshes)"
                : "at collision vertices",
            sim.contact_params.friction, sim.contact_params.dissipation, sim.contact_params.transition_velocity,
            sim.stop_stiffness,
            command == "check"
                ? fmt::format(", in the generic checks between the joint's subtree inertia × ({:g} rad/s)² and "
                              "× ({:g} rad/s)²",
                              dynamics::kGenericStopFloorFrequency, dynamics::kGenericStopFrequency)
                : ""),
        4);
    if (command == "check-tank") {
      auto link = [&](LinkIndex i) { return i >= 0 ? model->links[i].name : std::string("none"); };
      std::cout << tools::wrap(
          fmt::format("  tracks: left \"{}\", right \"{}\" (found by position), spacing B = {} m; turret yaw \"{}\", "
                      "pitch \"{}\", servo P = {:g}, D = {:g}",
                      link(tank.left), link(tank.right), number(tank.spacing), link(tank.yaw), link(tank.pitch),
                      suite.p_gain, suite.d_gain),
          4);
      if (!cross_check.empty())
        std::cout << tools::wrap(
            "  cross-check: MuJoCo 2.2.2 on body2mjcf's export (elliptic cones, Euler 1 ms, belt velocity through "
            "mjcb_control), the same commands in both engines; its \"MuJoCo vs Simbody\" lines: measured = MuJoCo, "
            "expected = Simbody",
            4);
    }
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
    if (command == "check" && !cross_check.empty()) std::cout << dynamics::describe(drop_report);
#endif
    print_results(results);
    bool failed = false;
    for (const auto& r : results) failed = failed || (!r.passed && !r.skipped);
    const int code = finish(false, "");
    return code == tools::kExitFatal ? code : (failed ? tools::kExitFindings : code);
  } catch (const dynamics::EngineFailure& e) {
    report_rule(sink, "dynamics-engine-failure", e.where, e.what());
    return finish(true,
                  "the simulation failed" + std::string(command == "run" ? "; " + csv_path + " was not written" : ""));
  } catch (const dynamics::WorkBudgetExceeded& e) {
    report_rule(sink, "dynamics-work-budget", e.where, e.what());
    return finish(
        true, "the simulation was stopped" + std::string(command == "run" ? "; " + csv_path + " was not written" : ""));
  } catch (const std::exception& e) {
    return finish(true, std::string("the simulation failed: ") + e.what());
  }
}
