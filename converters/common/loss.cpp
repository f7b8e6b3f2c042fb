#include <bodyfmt/converters/loss.h>

#include <bodyfmt/rules.h>
#include <fmt/format.h>

namespace bodyfmt::converters {

void report_loss(DiagnosticSink& sink, const SourceLocation& location, std::string_view target, std::string_view what,
                 std::string_view hint) {
  report_rule(sink, "export-loss", location, fmt::format("{} cannot express {}", target, what), std::string(hint));
}

}  // namespace bodyfmt::converters
