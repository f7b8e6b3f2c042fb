#include <bodyfmt/load.h>

#include "load/body_reader.h"

#include <fstream>
#include <sstream>

namespace bodyfmt {

std::optional<Model> load_body(const std::string& path, const LoadOptions& options, DiagnosticSink& sink) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    Diagnostic d;
    d.severity = Severity::kFatal;
    d.rule_id = "io-read";
    d.message = "cannot open \"" + path + "\"";
    d.location.file = path;
    sink.report(std::move(d));
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return load_body_string(text.str(), path, options, sink);
}

std::optional<Model> load_body_string(const std::string& text, const std::string& file_name,
                                      const LoadOptions& options, DiagnosticSink& sink) {
  try {
    detail::LoadSession session;
    detail::BodyReader reader(options, sink, session);
    return reader.read(text, file_name);
  } catch (const std::exception& e) {
    // A broken invariant must not take the caller down; report it as fatal.
    Diagnostic d;
    d.severity = Severity::kFatal;
    d.rule_id = "internal-error";
    d.message = std::string("internal error while loading: ") + e.what();
    d.location.file = file_name;
    sink.report(std::move(d));
    return std::nullopt;
  }
}

}  // namespace bodyfmt
