#include "render.h"

#include "gltf_writer.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/validate.h>

namespace bodyfmt::bodyview {
namespace {

/// Forwards what the GLB writer cannot do at all (a fatal export-write); its export losses
/// concern the GLB, not what the page shows.
class FatalOnly : public DiagnosticSink {
 public:
  explicit FatalOnly(DiagnosticSink& inner) : inner_(inner) {}
  void report(Diagnostic d) override {
    if (d.severity == Severity::kFatal) inner_.report(std::move(d));
  }

 private:
  DiagnosticSink& inner_;
};

}  // namespace

Rendered render(tools::Front& front, const tools::Front::FilePolicy& policy, const std::string& path,
                const std::filesystem::path& assets, const std::string& serve_status_url) {
  Rendered result;
  CollectingSink collected;
  DiagnosticPolicy sink(collected, policy.options);
  try {
    if (auto input = front.open_input(path, sink)) {
      result.model = front.load(*input, sink);
      if (input->read_by_front) front.sources().add(input->name, input->text);
    }
    if (result.model) {
      const Model& model = *result.model;
      result.inputs = input_files(model);
      const Derived derived = compute_derived(model, sink);
      validate::check_model(model, derived, {}, sink);
      gltf::GltfOptions options;
      options.geometry = gltf::GeometrySet::kBoth;
      options.binary = true;
      options.version = BODYFMT_VERSION;
      converters::OutputSet glb("model.glb");
      FatalOnly fatal(sink);
      if (gltf::write_gltf(model, derived, options, glb, fatal) && glb.has("model.glb")) {
        PageInput page;
        page.model = &model;
        page.derived = &derived;
        page.glb = glb.files().at("model.glb");
        page.findings = collected.diagnostics();
        sort_diagnostics(page.findings);
        page.sources = &front.sources();
        page.serve_status_url = serve_status_url;
        std::string error;
        result.page = build_page(assets, page, error);
        if (!result.page) sink.report(make_diagnostic("export-write", SourceLocation{model.source_file, 0, 0}, error));
      }
    }
  } catch (const std::exception& e) {
    sink.report(
        make_diagnostic("internal-error", SourceLocation{path, 0, 0}, std::string("unexpected failure: ") + e.what()));
    result.page.reset();
  }
  result.diagnostics = collected.diagnostics();
  sort_diagnostics(result.diagnostics);
  return result;
}

}  // namespace bodyfmt::bodyview
