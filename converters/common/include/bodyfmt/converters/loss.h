#pragma once
/// Reporting what a target format cannot express (rule `export-loss`, a warning by default;
/// a DiagnosticPolicy with `strict` makes it an error).
#include <bodyfmt/diagnostic.h>

#include <string>
#include <string_view>

namespace bodyfmt::converters {

/// Reports `export-loss` at `location` (the element's source line):
/// "<target> cannot express <what>", with `hint` as the fix hint.
void report_loss(DiagnosticSink& sink, const SourceLocation& location, std::string_view target, std::string_view what,
                 std::string_view hint = {});

}  // namespace bodyfmt::converters
