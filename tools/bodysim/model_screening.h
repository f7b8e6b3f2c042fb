#pragma once
/// What stops a loaded model before any engine sees it: errors of the file, more links than
/// --max-links, bodycheck's errors (the validator runs first), and under --contact simbody a
/// collision shape Simbody's contact does not take.

#include "run_diagnostics.h"
#include "sim_command.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/model.h>

#include <optional>
#include <string>

namespace bodyfmt::tools {

struct Screening {
  std::optional<Derived> derived;  ///< the model's derived data, when it may be simulated
  std::string refusal;             ///< otherwise why nothing is simulated
};

/// Screens `model` for `command`, reporting what refuses it through `run`.
Screening screen_model(const Model& model, const SimCommand& command, RunDiagnostics& run);

}  // namespace bodyfmt::tools
