#include <bodyfmt/diagnostic.h>
#include <doctest/doctest.h>

TEST_CASE("diagnostic format is file:line:col: severity: message [rule]") {
  bodyfmt::Diagnostic d;
  d.severity = bodyfmt::Severity::kWarning;
  d.rule_id = "yaml-duplicate-key";
  d.message = "duplicate key \"type\"";
  d.location = {"a.body", 3, 5};
  CHECK(bodyfmt::format_diagnostic(d) == "a.body:3:5: warning: duplicate key \"type\" [yaml-duplicate-key]");
}
