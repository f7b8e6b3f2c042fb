#include "load/load_context.h"

#include <bodyfmt/rules.h>

#include <cmath>

namespace bodyfmt::detail {

void LoadContext::report(std::string_view rule, const yaml::NodeRef& at, std::string message, std::string hint) {
  if (!at) return report(rule, SourceLocation{}, std::move(message), std::move(hint));
  // Point at the text responsible; when it was reached through an alias (directly or as
  // part of shared text), `via` names the alias use that led to it (style.md §2.3).
  std::optional<SourceLocation> via = at.alias_site ? at.alias_site : at.enclosing_alias;
  emit(rule, at->location, std::move(via), std::move(message), std::move(hint));
}

void LoadContext::report(std::string_view rule, const SourceLocation& at, std::string message, std::string hint) {
  emit(rule, at, std::nullopt, std::move(message), std::move(hint));
}

void LoadContext::emit(std::string_view rule, const SourceLocation& at, std::optional<SourceLocation> via,
                       std::string message, std::string hint) {
  if (!reported.emplace(std::string(rule), at.file, at.line, at.column, message).second) return;
  Diagnostic d = make_diagnostic(rule, at, std::move(message), std::move(hint));
  d.via = std::move(via);
  if (d.severity >= Severity::kError) ++errors;
  sink.report(std::move(d));
}

double LoadContext::angle(double value) const { return degrees ? value * M_PI / 180.0 : value; }

}  // namespace bodyfmt::detail
