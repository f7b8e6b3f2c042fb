#include "scenario_command.h"

#include "output_guard.h"
#include "report_lines.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/converters/protect_inputs.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

#include <iostream>
#include <sstream>
#include <vector>

namespace bodyfmt::tools {

int run_scenario_command(const SimCommand& command, const Model& model, const Derived& derived, RunDiagnostics& run) {
  const dynamics::SimOptions& sim = command.suite.sim;
  const std::string& scenario_path = command.scenario_path;
  const std::string& csv_path = command.csv_path;
  DiagnosticSink& sink = run.sink();
  // Refused before the simulation rather than after it (OutputSet refuses it again).
  std::vector<InputFile> inputs = input_files(model);
  inputs.push_back({scenario_path, "the scenario"});
  const std::string clash = input_clash(csv_path, inputs);
  if (!clash.empty()) {
    report_rule(sink, "export-write", SourceLocation{csv_path, 0, 0},
                fmt::format("cannot write '{}': {}; nothing was written", csv_path, clash));
    return run.finish(true, csv_path + " was not written");
  }
  std::optional<dynamics::ScenarioSpec> scenario = dynamics::read_scenario(scenario_path, model, sink);
  if (!scenario) return run.finish(true, "the scenario cannot be read; nothing was simulated");
  dynamics::ScenarioLimits limits = command.limits;
  limits.max_steps_per_second = sim.max_steps_per_second;
  if (!dynamics::check_scenario(*scenario, limits, sink))
    return run.finish(true, "the scenario is refused; nothing was simulated");
  std::ostringstream csv;
  dynamics::RunStats stats;
  if (!dynamics::run_scenario(model, derived, *scenario, sim, csv, sink, &stats))
    return run.finish(true, csv_path + " was not written");
  converters::OutputSet out(csv_path);
  converters::protect_inputs(out, model);
  out.protect(scenario_path, "the scenario");
  out.set_main(csv.str());
  if (!out.commit(sink)) return run.finish(true, csv_path + " was not written");
  // With the table on standard output (-o -), the summary goes beside the diagnostics.
  (out.to_stdout() ? std::cerr : std::cout) << fmt::format(
      "bodysim run: {} s of {} simulated in {} Runge-Kutta-Merson steps, {} force evaluations "
      "(accuracy {:g}); wrote {}\n",
      number(scenario->duration), model.name, stats.steps, stats.evaluations, sim.accuracy, csv_path);
  return run.finish(false, "");
}

}  // namespace bodyfmt::tools
