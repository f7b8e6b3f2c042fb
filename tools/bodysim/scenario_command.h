#pragma once
/// `bodysim run`: a scenario simulated and its trajectories written as CSV, atomically, never
/// over an input of the run.

#include "run_diagnostics.h"
#include "sim_command.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/model.h>

namespace bodyfmt::tools {

/// Runs `command`'s scenario on `model` and writes its CSV; returns the exit code.
int run_scenario_command(const SimCommand& command, const Model& model, const Derived& derived, RunDiagnostics& run);

}  // namespace bodyfmt::tools
