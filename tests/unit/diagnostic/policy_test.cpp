// DiagnosticPolicy: enable/disable, werror, strict, inline suppressions, counts.
#include <bodyfmt/diagnostic_policy.h>

#include <doctest/doctest.h>

#include <sstream>

#include <filesystem>
#include <fstream>

using namespace bodyfmt;

namespace {

Diagnostic make(int line, Severity severity, std::string rule, std::string file = "m.body") {
  Diagnostic d;
  d.location = {std::move(file), line, 3};
  d.severity = severity;
  d.rule_id = std::move(rule);
  d.message = "m";
  return d;
}

}  // namespace

TEST_CASE("policy: disable drops a rule and enable wins, families match by prefix") {
  CollectingSink out;
  PolicyOptions options;
  options.disable = {"units-*", "yaml-duplicate-key"};
  options.enable = {"units-prismatic-millimetres"};
  DiagnosticPolicy policy(out, options);
  policy.report(make(1, Severity::kWarning, "yaml-duplicate-key"));
  policy.report(make(2, Severity::kWarning, "units-mesh-millimetres"));
  policy.report(make(3, Severity::kWarning, "units-prismatic-millimetres"));
  policy.report(make(4, Severity::kError, "load-joint-type"));
  policy.report(make(5, Severity::kFatal, "yaml-duplicate-key"));  // fatal is never dropped
  REQUIRE(out.diagnostics().size() == 3);
  CHECK(out.diagnostics()[0].rule_id == "units-prismatic-millimetres");
  CHECK(out.diagnostics()[1].rule_id == "load-joint-type");
  CHECK(out.diagnostics()[2].severity == Severity::kFatal);
  CHECK(policy.disabled_count() == 2);
  CHECK(policy.count(Severity::kWarning) == 1);
  CHECK(policy.error_count() == 2);
  CHECK(policy.counts_by_rule().at("units-prismatic-millimetres") == 1);
  CHECK(!policy.enabled("units-mesh-millimetres"));
  CHECK(policy.enabled("units-prismatic-millimetres"));
}

TEST_CASE("policy: per-rule severities raise or lower a rule, the last match wins, werror comes after") {
  CollectingSink out;
  PolicyOptions options;
  options.severities = {
      {"yaml-*", Severity::kError}, {"yaml-duplicate-key", Severity::kNote}, {"load-info-key", Severity::kWarning}};
  options.werror = true;
  DiagnosticPolicy policy(out, options);
  policy.report(make(1, Severity::kWarning, "yaml-duplicate-key"));
  policy.report(make(2, Severity::kWarning, "yaml-empty-key"));
  policy.report(make(3, Severity::kNote, "load-info-key"));
  policy.report(make(4, Severity::kWarning, "load-legacy-key"));
  policy.report(make(5, Severity::kFatal, "yaml-syntax"));  // fatal stays fatal
  REQUIRE(out.diagnostics().size() == 5);
  CHECK(out.diagnostics()[0].severity == Severity::kNote);
  CHECK(out.diagnostics()[1].severity == Severity::kError);
  CHECK(out.diagnostics()[2].severity == Severity::kError);  // raised to a warning, then werror
  CHECK(out.diagnostics()[3].severity == Severity::kError);
  CHECK(out.diagnostics()[4].severity == Severity::kFatal);
}

TEST_CASE("policy: werror turns warnings into errors, strict turns export-loss and export-value-changed into errors") {
  CollectingSink out;
  PolicyOptions options;
  options.werror = true;
  DiagnosticPolicy policy(out, options);
  policy.report(make(1, Severity::kWarning, "yaml-duplicate-key"));
  policy.report(make(2, Severity::kNote, "load-info-key"));
  CHECK(out.diagnostics()[0].severity == Severity::kError);
  CHECK(out.diagnostics()[1].severity == Severity::kNote);
  CHECK(policy.count(Severity::kWarning) == 0);
  CHECK(policy.count(Severity::kError) == 1);

  CollectingSink strict_out;
  PolicyOptions strict;
  strict.strict = true;
  DiagnosticPolicy strict_policy(strict_out, strict);
  strict_policy.report(make(1, Severity::kWarning, "export-loss"));
  strict_policy.report(make(2, Severity::kNote, "export-loss"));
  strict_policy.report(make(3, Severity::kWarning, "export-name"));
  strict_policy.report(make(4, Severity::kWarning, "export-value-changed"));  // a changed value is refused too
  CHECK(strict_out.diagnostics()[0].severity == Severity::kError);
  CHECK(strict_out.diagnostics()[1].severity == Severity::kError);
  CHECK(strict_out.diagnostics()[2].severity == Severity::kWarning);
  CHECK(strict_out.diagnostics()[3].severity == Severity::kError);
}

TEST_CASE("policy: suppressions read from a stream are those read from the text, CRLF lines too") {
  const std::string text =
      "a: 1  # bodycheck: disable=rule-a\r\n"
      "# bodycheck: disable=rule-b\r\n"
      "\r\n"
      "b: 2  # bodycheck: disable=rule-c";  // no final line break
  std::istringstream in(text);
  Suppressions streamed = Suppressions::from_stream(in);
  Suppressions whole = Suppressions::from_text(text);
  for (Suppressions* s : {&streamed, &whole}) {
    CHECK(s->suppresses(1, "rule-a"));
    CHECK(s->suppresses(3, "rule-b"));  // the next line, even a blank one
    CHECK(!s->suppresses(4, "rule-b"));
    CHECK(s->suppresses(4, "rule-c"));
    REQUIRE(s->directives().size() == 3);
    CHECK(s->directives()[2].column == 28);  // where the rule id is written
  }
}

TEST_CASE("policy: inline suppression on the same line and on the line before") {
  const std::string text =
      "a: 1  # bodycheck: disable=rule-a\n"                     // 1: covers line 1
      "# bodycheck: disable=rule-b, rule-c  because reasons\n"  // 2: covers line 4 (3 stacks)
      "  # bodycheck: disable=rule-d\n"                         // 3
      "b: 2\n"                                                  // 4
      "c: \"# bodycheck: disable=rule-e\"\n"                    // 5: inside a string, ignored
      "d: x#bodycheck: disable=rule-f\n"                        // 6: not a comment (no blank)
      "e: 3 #bodycheck:disable=fam-*\n";                        // 7
  Suppressions s = Suppressions::from_text(text);
  CHECK(s.suppresses(1, "rule-a"));
  CHECK(!s.suppresses(2, "rule-a"));
  CHECK(!s.suppresses(1, "rule-b"));
  CHECK(s.suppresses(4, "rule-b"));
  CHECK(s.suppresses(4, "rule-c"));
  CHECK(s.suppresses(4, "rule-d"));
  CHECK(!s.suppresses(4, "because"));
  CHECK(!s.suppresses(3, "rule-b"));
  CHECK(!s.suppresses(5, "rule-e"));
  CHECK(!s.suppresses(6, "rule-f"));
  CHECK(s.suppresses(7, "fam-x"));

  CollectingSink out;
  DiagnosticPolicy policy(out);
  policy.set_suppressions("m.body", s);
  policy.report(make(1, Severity::kError, "rule-a"));
  policy.report(make(4, Severity::kWarning, "rule-d"));
  policy.report(make(4, Severity::kWarning, "rule-x"));
  Diagnostic via = make(9, Severity::kError, "rule-a");
  via.via = SourceLocation{"m.body", 1, 1};  // suppressed at the alias use site
  policy.report(via);
  REQUIRE(out.diagnostics().size() == 1);
  CHECK(out.diagnostics()[0].rule_id == "rule-x");
  CHECK(policy.suppressed_count() == 3);
}

TEST_CASE("policy: suppressions are read from the file a diagnostic points at") {
  const std::string path = "policy_suppression_test.body";
  std::ofstream(path) << "x: 1\n# bodycheck: disable=yaml-duplicate-key\nx: 2\n";
  CollectingSink out;
  DiagnosticPolicy policy(out);
  policy.report(make(3, Severity::kWarning, "yaml-duplicate-key", path));
  policy.report(make(1, Severity::kWarning, "yaml-duplicate-key", path));
  policy.report(make(1, Severity::kWarning, "yaml-duplicate-key", "no/such/file.body"));
  CHECK(out.diagnostics().size() == 2);
  CHECK(policy.suppressed_count() == 1);
  std::filesystem::remove(path);
}

TEST_CASE("policy: rule patterns are checked against the rule table with did-you-mean") {
  CHECK(check_rule_pattern("yaml-duplicate-key").empty());
  CHECK(check_rule_pattern("units-*").empty());
  CHECK(check_rule_pattern("yaml-duplicat-key") ==
        "unknown rule id 'yaml-duplicat-key'; did you mean 'yaml-duplicate-key'?");
  CHECK(check_rule_pattern("nothing-like-it-*").find("--list-rules") != std::string::npos);
  CHECK(rule_pattern_matches("a-*", "a-b"));
  CHECK(!rule_pattern_matches("a-*", "ab"));
  CHECK(rule_pattern_matches("a", "a"));
}

TEST_CASE("policy: suppressions remember where each id is written and whether it was used") {
  Suppressions s = Suppressions::from_text("a: 1  # bodycheck: disable=rule-a, rule-b\n");
  REQUIRE(s.directives().size() == 2);
  CHECK(s.directives()[0].column == 28);
  CHECK(s.directives()[1].column == 36);
  CHECK(s.suppresses(1, "rule-b"));
  CHECK(!s.directives()[0].used);
  CHECK(s.directives()[1].used);
}
