// JSON output (docs/bodycheck-json.md). No JSON library is a dependency, so the document is
// written by hand; every string goes through text::json_quote.

#include <bodyfmt/report.h>

#include "text/text_util.h"

using bodyfmt::text::json_quote;

namespace bodyfmt {

namespace {

std::string_view json_severity(Severity s) {
  switch (s) {
    case Severity::kNote: return "note";
    case Severity::kWarning: return "warning";
    case Severity::kError: return "error";
    case Severity::kFatal: return "fatal";
  }
  return "error";
}

std::string location_json(const SourceLocation& loc) {
  return "{\"file\": " + json_quote(loc.file.str()) + ", \"line\": " + std::to_string(loc.line) +
         ", \"column\": " + std::to_string(loc.column) + "}";
}

}  // namespace

std::string format_json_report(const Report& report, const ToolInfo& tool) {
  std::string out = "{\n";
  out += "  \"version\": 1,\n";
  out += "  \"tool\": {\"name\": " + json_quote(tool.name) + ", \"version\": " + json_quote(tool.version) + "},\n";
  out += "  \"files\": [";
  for (std::size_t i = 0; i < report.files.size(); ++i) {
    out += i == 0 ? "\n    " : ",\n    ";
    out += json_quote(report.files[i]);
  }
  out += report.files.empty() ? "],\n" : "\n  ],\n";
  out += "  \"diagnostics\": [";
  for (std::size_t i = 0; i < report.diagnostics.size(); ++i) {
    const Diagnostic& d = report.diagnostics[i];
    out += i == 0 ? "\n    {" : ",\n    {";
    out += "\"file\": " + json_quote(d.location.file.str());
    out += ", \"line\": " + std::to_string(d.location.line);
    out += ", \"column\": " + std::to_string(d.location.column);
    out += ", \"severity\": " + json_quote(json_severity(d.severity));
    out += ", \"rule\": " + json_quote(d.rule_id);
    out += ", \"message\": " + json_quote(d.message);
    out += ", \"via\": " + (d.via ? location_json(*d.via) : std::string("null"));
    out += ", \"fix_hint\": " + (d.fix_hint.empty() ? std::string("null") : json_quote(d.fix_hint));
    out += ", \"fixes\": [";
    for (std::size_t k = 0; k < d.fixes.size(); ++k) {
      const FixIt& f = d.fixes[k];
      out += k == 0 ? "" : ", ";
      out += "{\"file\": " + json_quote(f.file.str()) + ", \"line\": " + std::to_string(f.line) +
             ", \"column\": " + std::to_string(f.column) + ", \"offset\": " + std::to_string(f.begin) +
             ", \"length\": " + std::to_string(f.end - f.begin) + ", \"original\": " + json_quote(f.original) +
             ", \"replacement\": " + json_quote(f.replacement) +
             ", \"safety\": " + json_quote(fix_safety_name(f.safety)) + "}";
    }
    out += "]}";
  }
  out += report.diagnostics.empty() ? "],\n" : "\n  ],\n";
  out += "  \"summary\": {";
  out += "\"files\": " + std::to_string(report.files.size());
  out += ", \"fatal\": " + std::to_string(report.count(Severity::kFatal));
  out += ", \"errors\": " + std::to_string(report.count(Severity::kError));
  out += ", \"warnings\": " + std::to_string(report.count(Severity::kWarning));
  out += ", \"notes\": " + std::to_string(report.count(Severity::kNote));
  out += ", \"suppressed\": " + std::to_string(report.suppressed);
  out += ", \"disabled\": " + std::to_string(report.disabled);
  out += ", \"by_rule\": {";
  bool first = true;
  for (const auto& [rule, n] : report.counts_by_rule()) {
    out += first ? "" : ", ";
    first = false;
    out += json_quote(rule) + ": " + std::to_string(n);
  }
  out += "}}\n}\n";
  return out;
}

}  // namespace bodyfmt
