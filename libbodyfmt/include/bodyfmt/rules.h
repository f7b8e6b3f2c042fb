#pragma once
/// The rule table: every diagnostic id the project can report, with its default severity and
/// documentation. One row per id feeds `--list-rules`, docs/rules.md, SARIF rule metadata and
/// `--enable` / `--disable`. An id is never reused.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>

#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

struct RuleInfo {
  std::string_view id;         ///< kebab-case with a family prefix, e.g. "inertia-triangle"
  Severity default_severity;   ///< what the reporting stage uses unless a policy changes it
  std::string_view summary;    ///< one line: what is wrong
  std::string_view rationale;  ///< one line: why it matters (which tool fails, what is lost)
  std::string_view tolerance;  ///< documented tolerance, empty when the rule has none
  /// The fix-its the rule's findings carry and how safe they are (FixSafety): "safe" (applied by
  /// `bodycheck --fix`), "upgrade" (only with `--fix --upgrade`), "unsafe" (shown, never
  /// applied), or empty when the rule has none. Set from one list in the rule table.
  std::string_view fix = {};
};

/// Every rule, sorted by id.
const std::vector<RuleInfo>& all_rules();

/// The row of `id`, or nullptr.
const RuleInfo* find_rule(std::string_view id);

/// The one way to make a diagnostic: its severity is the rule's default from the table (a
/// DiagnosticPolicy may change it later; an id missing from the table, which a test forbids,
/// gives an error).
Diagnostic make_diagnostic(std::string_view rule_id, SourceLocation location, std::string message,
                           std::string fix_hint = {});
/// sink.report(make_diagnostic(...)).
void report_rule(DiagnosticSink& sink, std::string_view rule_id, SourceLocation location, std::string message,
                 std::string fix_hint = {});

}  // namespace bodyfmt
#pragma GCC visibility pop
