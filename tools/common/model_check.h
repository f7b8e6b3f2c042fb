#pragma once
/// bodycheck's check of one model file, shared by bodycheck and bodyls so that the language
/// server publishes exactly the findings the command line reports: the same loader options,
/// rules, `.bodycheck.yaml` policy, suppressions and severities.

#include "front.h"

#include <bodyfmt/input_files.h>
#include <bodyfmt/model.h>

#include <memory>
#include <vector>

namespace bodyfmt::tools {

struct ModelCheck {
  std::vector<Diagnostic> diagnostics;  ///< in arrival order
  std::vector<InputFile> inputs;        ///< the files the model was read from (when asked for)
  std::shared_ptr<const Model> model;   ///< the model (when asked for and it loaded)
  bool loaded = false;
  int suppressed = 0;
  int disabled = 0;
};

struct ModelCheckWants {
  bool inputs = false;  ///< fill ModelCheck::inputs
  bool model = false;   ///< keep the model in ModelCheck::model
};

/// Loads `input` (its text when the front or the editor read it, else the file) with `options`
/// and runs every rule under `policy`. Suppression comments are read from the text checked.
ModelCheck check_model_input(const LoadOptions& options, const ModelInput& input, const PolicyOptions& policy,
                             ModelCheckWants wants = {});

/// Sorts `diagnostics` and drops repeats: a file included several times (SubBody) reports the
/// same finding each time.
void sort_unique_findings(std::vector<Diagnostic>& diagnostics);

}  // namespace bodyfmt::tools
