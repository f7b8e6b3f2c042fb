#pragma once
/// The run every exporter shares: read the model (a .body file through the front's policy, or
/// another format through the tool's reader), let the writer stage the output, commit it only
/// when nothing forbids it (errors, --strict losses, a writer that failed), print the
/// diagnostics and return the exit code.

#include "front.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::tools {

/// Stages the export of `model` in `out`; false when the output is unusable (reported).
using ExportWriter =
    std::function<bool(const Model& model, const Derived& derived, converters::OutputSet& out, DiagnosticSink& sink)>;
/// A tool's own reason why nothing was written (e.g. "MuJoCo refuses an inertia ..."), or empty.
using RefusalReason = std::function<std::string(const std::vector<Diagnostic>& diagnostics)>;

/// Runs the export of the front's one .body input to `output`.
int run_export(Front& front, const std::string& output, const ExportWriter& write, const RefusalReason& refusal = {});

/// The steps of an export whose input is not a .body file (urdf2body's URDF).
struct ExportSteps {
  /// Reads the opened input into a model; nullopt when it cannot (reported).
  std::function<std::optional<Model>(const ModelInput& input, DiagnosticSink& sink)> read;
  /// Stages the export of `model` in `out`, which already protects the model's inputs. The model
  /// is the run's own: the stage may point it at the files it stages. False when the output is
  /// unusable (reported).
  std::function<bool(Model& model, converters::OutputSet& out, DiagnosticSink& sink)> stage;
  RefusalReason refusal;
};

/// Runs the export of the front's one input to `output` through `steps`.
int run_export(Front& front, const std::string& output, const ExportSteps& steps);

/// A CLI11 check for folders of generated files: relative, and inside the output's folder.
std::string check_inside_output_folder(const std::string& folder);

}  // namespace bodyfmt::tools
