// The scenario values the reader takes as they are, judged: bodysim's limits of simulated time
// and rows, and servo gains (issue 26).
#include <bodyfmt/dynamics/scenario.h>

#include <bodyfmt/rules.h>

#include <fmt/format.h>

#include <algorithm>

namespace bodyfmt::dynamics {

bool check_scenario(const ScenarioSpec& scenario, const ScenarioLimits& limits, DiagnosticSink& sink) {
  bool ok = true;
  const auto refuse = [&](const SourceLocation& at, std::string message, std::string hint) {
    report_rule(sink, "dynamics-scenario", at, std::move(message), std::move(hint));
    ok = false;
  };
  if (scenario.duration > limits.max_duration)
    refuse(scenario.duration_at,
           fmt::format("'duration' {:g} s is more than bodysim simulates (--max-duration {:g} s)", scenario.duration,
                       limits.max_duration),
           "raise --max-duration to simulate it anyway; a simulated second takes from milliseconds to seconds");
  const double rows = scenario.duration / scenario.sample;
  if (rows > limits.max_rows)
    refuse(scenario.sample_at.known() ? scenario.sample_at : scenario.duration_at,
           fmt::format("'duration' / 'sample' gives {:g} rows, more than --max-rows {:g}", rows, limits.max_rows),
           "sample less often, or raise --max-rows");
  if (static_cast<double>(scenario.commands.size()) > limits.max_commands)
    refuse(scenario.commands[static_cast<std::size_t>(limits.max_commands)].at,
           fmt::format("the scenario has {} commands, more than --max-commands {:g}; this is the first over the limit",
                       scenario.commands.size(), limits.max_commands),
           "raise --max-commands to run it anyway");
  if (limits.max_steps_per_second > 0) {
    // The budget is looked at against max(1 s, t) (Simulation::check_budget); only a
    // scenario that cannot stay within it is refused here.
    long long restarts = 0;
    double last = 0;
    for (const ScenarioCommand& command : scenario.commands) {
      if (command.time <= last || command.time > scenario.duration) continue;
      last = command.time;
      if (static_cast<double>(++restarts) <= limits.max_steps_per_second * std::max(1.0, command.time)) continue;
      refuse(command.at,
             fmt::format("the commands change the inputs at {} distinct times by t = {:g} s, and each restarts the "
                         "integrator: more steps than --max-steps-per-second {:g} allows by then",
                         restarts, command.time, limits.max_steps_per_second),
             "give commands that belong together one time, or raise --max-steps-per-second");
      break;
    }
  }
  for (const ScenarioCommand& command : scenario.commands)
    for (const auto& [link, servo] : command.joints) {
      if (servo.p && *servo.p < 0)
        refuse(servo.p_at,
               fmt::format("the gain 'p' {:g} is negative: the servo would push away from its target", *servo.p),
               "a PD servo's gains are zero or positive (N·m/rad or N/m)");
      if (servo.d && *servo.d < 0)
        refuse(servo.d_at, fmt::format("the gain 'd' {:g} is negative: the servo would feed energy in", *servo.d),
               "a PD servo's gains are zero or positive (N·m·s/rad or N·s/m)");
    }
  return ok;
}

}  // namespace bodyfmt::dynamics
