#pragma once
/// What `bodysim check-tank` and `bodysim check` print on standard output: the model and the
/// engine's settings, then every check.

#include "sim_command.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/dynamics/checks.h>
#include <bodyfmt/model.h>

#include <string>
#include <vector>

namespace bodyfmt::tools {

/// The model (read from `path`), the engine and its settings, and for check-tank the tank's
/// layout and the cross-check's.
void print_check_header(const SimCommand& command, const std::string& path, const Model& model, const Derived& derived,
                        const dynamics::TankLayout& tank);

/// The model's checks, then the build's self-test apart, then the counts.
void print_results(const std::vector<dynamics::CheckResult>& results);

}  // namespace bodyfmt::tools
