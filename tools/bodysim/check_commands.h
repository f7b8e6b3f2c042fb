#pragma once
/// `bodysim check-tank` and `bodysim check`: the tank suite or the generic checks in Simbody,
/// with MuJoCo's cross-check when asked, reported check by check.

#include "run_diagnostics.h"
#include "sim_command.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/model.h>

#include <string>

namespace bodyfmt::tools {

/// Runs `command`'s checks on `model` (read from `path`) and prints them; returns the exit
/// code (1 when a check failed).
int run_check_command(const SimCommand& command, const std::string& path, const Model& model, const Derived& derived,
                      RunDiagnostics& run);

}  // namespace bodyfmt::tools
