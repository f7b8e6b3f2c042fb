#include "model_check.h"

#include "compact_findings.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/validate.h>

#include <algorithm>

namespace bodyfmt::tools {

ModelCheck check_model_input(const LoadOptions& options, const ModelInput& input, const PolicyOptions& policy_options,
                             ModelCheckWants wants) {
  ModelCheck result;
  // Compact while the model is alive: a generated model can have a finding per link.
  CompactFindings collected;
  DiagnosticPolicy policy(collected, policy_options);
  // Text not read from its file (standard input, an editor's unsaved buffer) carries its own
  // suppression comments; the policy would read them from the file.
  if (input.read_by_front) policy.set_suppressions(input.name, Suppressions::from_text(input.text));
  try {
    std::optional<Model> model = input.read_by_front ? load_body_string(input.text, input.name, options, policy)
                                                     : load_body(input.path, options, policy);
    result.loaded = model.has_value();
    if (model && wants.inputs) result.inputs = input_files(*model);
    if (model) {
      Derived derived = compute_derived(*model, policy);
      validate::check_model(*model, derived, {}, policy);
      // Only bodycheck runs every rule, so only it can tell that a suppression is unused.
      if (input.path != "-" || input.read_by_front) policy.report_suppression_problems(input.name);
      if (wants.model) result.model = std::make_shared<const Model>(std::move(*model));
    }
  } catch (const std::exception& e) {
    policy.report(make_diagnostic("internal-error", SourceLocation{input.name, 0, 0},
                                  std::string("unexpected failure: ") + e.what()));
    result.loaded = false;
  }
  result.diagnostics = collected.take();
  result.suppressed = policy.suppressed_count();
  result.disabled = policy.disabled_count();
  return result;
}

namespace {
bool same_diagnostic(const Diagnostic& a, const Diagnostic& b) {
  return a.location == b.location && a.rule_id == b.rule_id && a.message == b.message && a.severity == b.severity;
}
}  // namespace

void sort_unique_findings(std::vector<Diagnostic>& diagnostics) {
  sort_diagnostics(diagnostics);
  diagnostics.erase(std::unique(diagnostics.begin(), diagnostics.end(), same_diagnostic), diagnostics.end());
}

}  // namespace bodyfmt::tools
