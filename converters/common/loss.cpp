#include <bodyfmt/converters/loss.h>

#include <fmt/format.h>

namespace bodyfmt::converters {

void report_loss(DiagnosticSink& sink, const SourceLocation& location, std::string_view target,
                 std::string_view what, std::string_view hint) {
  Diagnostic d;
  d.severity = Severity::kWarning;
  d.rule_id = "export-loss";
  d.message = fmt::format("{} cannot express {}", target, what);
  d.location = location;
  d.fix_hint = std::string(hint);
  sink.report(std::move(d));
}

}  // namespace bodyfmt::converters
