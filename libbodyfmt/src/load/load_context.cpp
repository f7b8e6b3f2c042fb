#include "load/load_context.h"

#include <cmath>

namespace bodyfmt::detail {

void LoadContext::report(Severity severity, std::string_view rule, const yaml::NodeRef& at,
                         std::string message, std::string hint) {
  Diagnostic d;
  d.severity = severity;
  d.rule_id = std::string(rule);
  d.message = std::move(message);
  d.fix_hint = std::move(hint);
  if (at) {
    // Point at the text the reader sees; when that is an alias, also name the anchor's value.
    d.location = at.use_site();
    if (at.alias_site) d.via = at->location;
    else if (at.enclosing_alias) d.via = at.enclosing_alias;
  }
  if (severity >= Severity::kError) ++errors;
  sink.report(std::move(d));
}

void LoadContext::report(Severity severity, std::string_view rule, const SourceLocation& at,
                         std::string message, std::string hint) {
  Diagnostic d;
  d.severity = severity;
  d.rule_id = std::string(rule);
  d.message = std::move(message);
  d.fix_hint = std::move(hint);
  d.location = at;
  if (severity >= Severity::kError) ++errors;
  sink.report(std::move(d));
}

double LoadContext::angle(double value) const { return degrees ? value * M_PI / 180.0 : value; }

}  // namespace bodyfmt::detail
