#include "check_commands.h"

#include "check_report.h"

#include <bodyfmt/dynamics/checks.h>
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
#include <bodyfmt/dynamics/drop_cross_check.h>
#endif

#include <iostream>
#include <vector>

namespace bodyfmt::tools {

int run_check_command(const SimCommand& command, const std::string& path, const Model& model, const Derived& derived,
                      RunDiagnostics& run) {
  const dynamics::TankSuiteOptions& suite = command.suite;
  DiagnosticSink& sink = run.sink();
  std::string why;
  std::vector<dynamics::CheckResult> results;
  dynamics::TankLayout tank;
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
  dynamics::DropCrossCheckReport drop_report;
#endif
  if (command.name == "check-tank") {
    results = dynamics::run_tank_suite(model, derived, suite, sink, why, &tank);
    if (!results.empty() && !command.cross_check.empty()) {
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
      std::vector<dynamics::CheckResult> cross = dynamics::run_mujoco_cross_check(model, derived, suite, sink, why);
      if (cross.empty()) return run.finish(true, why.empty() ? "the MuJoCo cross-check failed" : why);
      results.insert(results.end(), cross.begin(), cross.end());
#else
      return run.finish(true, "this bodysim was built without MuJoCo: --cross-check mujoco is unavailable");
#endif
    }
  } else {
    results = dynamics::run_generic_checks(model, derived, suite.sim, sink, why);
    if (!results.empty() && !command.cross_check.empty()) {
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
      dynamics::DropCrossCheckOptions drop;
      drop.sim = suite.sim;
      std::vector<dynamics::CheckResult> cross =
          dynamics::run_drop_cross_check(model, derived, drop, sink, why, &drop_report);
      if (cross.empty()) return run.finish(true, why.empty() ? "the MuJoCo cross-check failed" : why);
      results.insert(results.end(), cross.begin(), cross.end());
#else
      return run.finish(true, "this bodysim was built without MuJoCo: --cross-check mujoco is unavailable");
#endif
    }
  }
  if (results.empty()) return run.finish(true, why.empty() ? "nothing was simulated" : why + "; nothing was simulated");
  print_check_header(command, path, model, derived, tank);
#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
  if (command.name == "check" && !command.cross_check.empty()) std::cout << dynamics::describe(drop_report);
#endif
  print_results(results);
  bool failed = false;
  for (const auto& r : results) failed = failed || (!r.passed && !r.skipped);
  const int code = run.finish(false, "");
  return code == kExitFatal ? code : (failed ? kExitFindings : code);
}

}  // namespace bodyfmt::tools
