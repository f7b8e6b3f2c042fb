#include <bodyfmt/load.h>

#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>
#include "load/body_reader.h"
#include "load/resource_reader.h"

#include <fstream>
#include <sstream>

namespace bodyfmt {

namespace {

std::optional<Model> load_body_text(std::string_view text, const std::string& file_name, const LoadOptions& options,
                                    DiagnosticSink& sink) {
  try {
    // The file asked for is quoted even when it is not YAML: its syntax errors need the line.
    detail::note_model_text(options, file_name);
    detail::LoadSession session;
    detail::BodyReader reader(options, sink, session);
    return reader.read(text, file_name);
  } catch (const std::exception& e) {
    // A broken invariant must not take the caller down; report it as fatal.
    report_rule(sink, "internal-error", SourceLocation{file_name, 0, 0},
                std::string("internal error while loading: ") + e.what());
    return std::nullopt;
  }
}

}  // namespace

std::optional<Model> load_body(const std::string& path, const LoadOptions& options, DiagnosticSink& sink) {
  std::string why;
  const std::optional<detail::FileBytes> bytes = detail::read_regular_file_bytes(path, options.max_file_bytes, why);
  if (!bytes) {
    report_rule(sink, "io-read", SourceLocation{path, 0, 0}, "cannot read \"" + path + "\": " + why);
    return std::nullopt;
  }
  return load_body_text(bytes->view(), path, options, sink);
}

std::optional<Model> load_body_string(const std::string& text, const std::string& file_name, const LoadOptions& options,
                                      DiagnosticSink& sink) {
  return load_body_text(text, file_name, options, sink);
}

}  // namespace bodyfmt
