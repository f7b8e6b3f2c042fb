#include "export_run.h"

#include "export_summary.h"

#include <bodyfmt/converters/protect_inputs.h>

#include <filesystem>
#include <iostream>

namespace bodyfmt::tools {

int run_export(Front& front, const std::string& output, const ExportWriter& write, const RefusalReason& refusal) {
  ExportSteps steps;
  steps.read = [&front](const ModelInput& input, DiagnosticSink& sink) { return front.load(input, sink); };
  // Derived data is the .body exporters' (computed before the writer, as it reports through
  // the same sink); urdf2body writes the model as it was read.
  steps.stage = [&write](Model& model, converters::OutputSet& out, DiagnosticSink& sink) {
    const Derived derived = compute_derived(model, sink);
    return write(model, derived, out, sink);
  };
  steps.refusal = refusal;
  return run_export(front, output, steps);
}

int run_export(Front& front, const std::string& output, const ExportSteps& steps) {
  const std::string& path = front.inputs().front();
  auto policy = front.policy_for(path);
  if (!policy) return kExitFatal;
  CollectingSink collected;
  DiagnosticPolicy sink(collected, policy->options);  // --strict: export-loss is an error
  bool written = false;
  bool refused_by_writer = false;
  bool commit_failed = false;
  std::string summary;
  if (auto input = front.open_input(path, sink)) {
    auto model = steps.read(*input, sink);
    if (model && front.may_write(collected.diagnostics())) {
      converters::OutputSet out(output);
      converters::protect_inputs(out, *model);
      // --strict losses and export errors stop the write, as loader errors did above.
      refused_by_writer = !steps.stage(*model, out, sink);
      if (!refused_by_writer && front.may_write(collected.diagnostics())) {
        written = out.commit(sink);
        commit_failed = !written;  // reported with its reason (export-write)
        if (written) summary = export_summary(out, collected.diagnostics(), policy->exit);
      }
    }
  }
  const std::vector<Diagnostic>& diagnostics = collected.diagnostics();
  front.print(diagnostics);
  if (written) std::cerr << front.tool_name() << ": " << summary << '\n';
  if (!written) {
    std::string why = steps.refusal && !commit_failed ? steps.refusal(diagnostics) : std::string();
    if (why.empty() && refused_by_writer) why = "the model has errors this format cannot be written with";
    if (why.empty() && !commit_failed && !front.may_write(diagnostics))
      why = "the model has errors (--best-effort writes it anyway)";
    front.print_error(output + " was not written" + (why.empty() ? "" : ": " + why));
  }
  return exit_code(diagnostics, policy->exit, !written);
}

std::string check_inside_output_folder(const std::string& folder) {
  const std::filesystem::path path(folder);
  bool inside = !folder.empty() && path.is_relative();
  for (const auto& part : path) inside = inside && part != "..";
  return inside ? std::string() : "the mesh folder must be a relative path inside the output file's folder";
}

}  // namespace bodyfmt::tools
