#pragma once
/// The run every exporter shares: load the model through the front's policy, derive its data,
/// let the writer stage the output, commit it only when nothing forbids it (errors, --strict
/// losses, a writer that failed), print the diagnostics and return the exit code.

#include "front.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>

#include <functional>
#include <string>
#include <vector>

namespace bodyfmt::tools {

/// Stages the export of `model` in `out`; false when the output is unusable (reported).
using ExportWriter =
    std::function<bool(const Model& model, const Derived& derived, converters::OutputSet& out, DiagnosticSink& sink)>;
/// A tool's own reason why nothing was written (e.g. "MuJoCo refuses an inertia ..."), or empty.
using RefusalReason = std::function<std::string(const std::vector<Diagnostic>& diagnostics)>;

/// Runs the export of the front's one input to `output`.
int run_export(Front& front, const std::string& output, const ExportWriter& write, const RefusalReason& refusal = {});

/// A CLI11 check for folders of generated files: relative, and inside the output's folder.
std::string check_inside_output_folder(const std::string& folder);

}  // namespace bodyfmt::tools
