// The bodycheck command line on the small files of tests/data/bodycheck: exit codes, the
// located text, formats, options and configs. Run from inside that folder, so that paths in
// the output are relative and stable.
#include <doctest/doctest.h>

#include "support/run_command.h"

#include <filesystem>
#include <fstream>
#include <string>

namespace {

using Run = bodyfmt::test::CommandResult;  // stdout, then stderr when merged

Run bodycheck(const std::string& args, bool merge = true) {
  return bodyfmt::test::run_command("'" + std::string(BODYFMT_BODYCHECK) + "' " + args + (merge ? "" : " 2>/dev/null"),
                                    std::string(BODYFMT_TEST_DATA_DIR) + "/bodycheck", merge);
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

}  // namespace

TEST_CASE("bodycheck: a clean file exits 0 with a summary") {
  Run r = bodycheck("clean.body");
  CHECK(r.status == 0);
  CHECK(r.output == "bodycheck: 1 file checked: 0 errors, 0 warnings, 0 notes\n");
  CHECK(bodycheck("--quiet clean.body").output.empty());
}

TEST_CASE("bodycheck: an error exits 1 with the located message, source line and caret") {
  Run r = bodycheck("defective.body");
  CHECK(r.status == 1);
  CHECK(contains(r.output,
                 "defective.body:16:17: error: illegal joint type \"hinge\" [load-joint-type]\n"
                 "    joint_type: hinge\n"
                 "                ^\n"
                 "defective.body:16:17: note: use revolute"));
}

TEST_CASE("bodycheck: --fail-on, --werror and --disable decide the exit code") {
  CHECK(bodycheck("warning.body").status == 0);  // warnings do not fail by default
  CHECK(bodycheck("--fail-on warning warning.body").status == 1);
  Run werror = bodycheck("--werror warning.body");
  CHECK(werror.status == 1);
  CHECK(contains(werror.output, "warning.body:11:5: error: duplicate key \"mass\""));
  Run disabled = bodycheck("--disable yaml-duplicate-key --fail-on warning warning.body");
  CHECK(disabled.status == 0);
  CHECK(contains(disabled.output, "1 disabled"));
  CHECK(bodycheck("--disable load-joint-type defective.body").status == 0);
}

TEST_CASE("bodycheck: --severity and a config's severity: raise or lower one rule") {
  Run raised = bodycheck("--severity yaml-duplicate-key=error warning.body");
  CHECK(raised.status == 1);
  CHECK(contains(raised.output, "warning.body:11:5: error: duplicate key \"mass\""));
  Run lowered = bodycheck("--severity load-joint-type=warning defective.body");
  CHECK(lowered.status == 0);
  CHECK(contains(lowered.output, "warning: illegal joint type"));
  // The last setting of a rule wins; --werror still applies after it.
  CHECK(bodycheck("--severity yaml-duplicate-key=error,yaml-duplicate-key=note warning.body").status == 0);
  CHECK(bodycheck("--severity yaml-duplicate-key=note --werror warning.body").status == 0);
  CHECK(bodycheck("--severity yaml-*=warning --werror warning.body").status == 1);
  Run bad = bodycheck("--severity yaml-duplicat-key=error warning.body");
  CHECK(bad.status == 2);
  CHECK(contains(bad.output, "did you mean 'yaml-duplicate-key'"));
  CHECK(bodycheck("--severity yaml-duplicate-key=fatal warning.body").status == 2);
  CHECK(bodycheck("--severity yaml-duplicate-key warning.body").status == 2);
}

TEST_CASE("bodycheck: --explain prints a rule's documentation") {
  Run r = bodycheck("--explain load-unknown-model-key", false);
  CHECK(r.status == 0);
  CHECK(r.output.rfind("load-unknown-model-key: error by default\n  what:      an unknown key close to a key that "
                       "changes the model",
                       0) == 0);
  CHECK(contains(r.output, "  fix-it:    unsafe: the did-you-mean key"));
  CHECK(contains(r.output, "--severity load-unknown-model-key=note|warning|error"));
  CHECK(bodycheck("--explain load-unknown").status == 2);
}

TEST_CASE("bodycheck: errors first, repeats folded, --min-severity, and the --fix command in the summary") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "bodyfmt_bodycheck_view_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // Four legacy keys (warnings with a safe fix-it) before an error on line 12.
  std::ofstream(dir / "m.body") << "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n"
                                   "  - name: A\n    jointType: free\n    centerOfMass: [0, 0, 0]\n"
                                   "    mass: 1\n    inertia: [1, 0, 0, 1, 0, 1]\n  - name: B\n    parent: A\n"
                                   "    jointType: revolute\n    joint_axis: Q\n    jointRange: [-1, 1]\n"
                                   "    jointId: 0\n    mass: 1\n    inertia: [1, 0, 0, 1, 0, 1]\n";
  const std::string file = (dir / "m.body").string();
  Run r = bodycheck("--no-config '" + file + "'", false);
  CHECK(r.status == 1);
  INFO(r.output);
  CHECK(r.output.rfind(file + ":12:17: error: ", 0) == 0);  // the error first
  CHECK(contains(r.output, file + ":5:5: warning: legacy key \"jointType\""));
  // The line list wraps at 100 columns, so where depends on the length of the path.
  CHECK(contains(r.output, file + ": note: 4 more [load-legacy-key] in this file, at lines 6,"));
  CHECK(contains(r.output, " 11, 13, 14\n"));
  CHECK(!contains(r.output, file + ":6:5: warning"));
  CHECK(contains(r.output, "bodycheck: --min-severity error prints the errors only\n"));
  CHECK(contains(r.output, "bodycheck: 5 findings have a safe fix-it: `bodycheck --fix " + file +
                               "` applies them (add --dry-run to see the diff first)\n"));
  Run errors = bodycheck("--no-config --min-severity error '" + file + "'", false);
  CHECK(errors.status == 1);
  CHECK(!contains(errors.output, "warning:"));
  CHECK(contains(errors.output, "bodycheck: 1 file checked: 1 error, 5 warnings, 0 notes\n"));
  CHECK(contains(errors.output, "bodycheck: 5 findings below error not shown (--min-severity)\n"));
  // JSON keeps every finding whatever the view.
  Run json = bodycheck("--no-config --min-severity error --format json '" + file + "'", false);
  std::size_t rules = 0;
  for (std::size_t at = json.output.find("\"rule\":"); at != std::string::npos;
       at = json.output.find("\"rule\":", at + 1))
    ++rules;
  CHECK(rules == 6);
  fs::remove_all(dir);
}

TEST_CASE("bodycheck: usage errors exit 2, unknown rule ids with did-you-mean") {
  Run r = bodycheck("--disable yaml-duplicat-key warning.body");
  CHECK(r.status == 2);
  CHECK(contains(r.output, "did you mean 'yaml-duplicate-key'?"));
  CHECK(bodycheck("--enable no-such-rule warning.body").status == 2);
  CHECK(bodycheck("--format xml warning.body").status == 2);
  CHECK(bodycheck("").status == 2);
  CHECK(bodycheck("no-such-file.body").status == 2);
  CHECK(bodycheck("--help").status == 0);
}

TEST_CASE("bodycheck: a file that cannot be loaded exits 2") {
  Run r = bodycheck("unloadable.body clean.body");
  CHECK(r.status == 2);
  CHECK(contains(r.output, "unloadable.body:5:1: fatal error: "));
  CHECK(contains(r.output, "[yaml-syntax]"));
}

TEST_CASE("bodycheck: inline suppressions") {
  Run r = bodycheck("--fail-on warning suppressed.body");
  CHECK(r.status == 0);
  CHECK(r.output == "bodycheck: 1 file checked: 0 errors, 0 warnings, 0 notes, 2 suppressed\n");
}

TEST_CASE("bodycheck: configs are found per file and the nearest wins") {
  // configured/.bodycheck.yaml disables yaml-duplicate-key; configured/strict/ has its own
  // config (fail_on: warning) without that, so only the inner file reports and fails.
  Run r = bodycheck("configured");
  CHECK(r.status == 1);
  CHECK(contains(r.output, "configured/strict/warning.body:11:5: warning: duplicate key"));
  CHECK(!contains(r.output, "configured/warning.body:"));
  CHECK(contains(r.output, "2 files checked"));
  CHECK(bodycheck("--fail-on error configured").status == 0);  // the command line wins
  CHECK(bodycheck("--no-config configured/warning.body --fail-on warning").status == 1);
  Run bad = bodycheck("bad_config/clean.body");
  CHECK(bad.status == 2);
  CHECK(contains(bad.output,
                 "bad_config/.bodycheck.yaml:2:11: error: unknown rule id 'yaml-duplicat-key'; did "
                 "you mean 'yaml-duplicate-key'? [config-invalid]"));
}

TEST_CASE("bodycheck: directories, order and formats") {
  // Output is sorted by file whatever the argument order and thread timing.
  Run a = bodycheck("-j 4 warning.body defective.body", false);
  Run b = bodycheck("-j 1 defective.body warning.body", false);
  CHECK(a.output == b.output);
  CHECK(a.output.find("defective.body:") < a.output.find("warning.body:"));

  Run json = bodycheck("--format json defective.body warning.body", false);
  CHECK(json.status == 1);
  CHECK(contains(json.output, "\"version\": 1,"));
  CHECK(contains(json.output,
                 "\"file\": \"defective.body\", \"line\": 16, \"column\": 17, \"severity\": \"error\", "
                 "\"rule\": \"load-joint-type\""));
  CHECK(contains(json.output, "\"summary\": {\"files\": 2,"));

  Run sarif = bodycheck("--format sarif defective.body", false);
  CHECK(sarif.status == 1);
  CHECK(contains(sarif.output, "\"version\": \"2.1.0\""));
  CHECK(contains(sarif.output, "\"ruleId\": \"load-joint-type\""));
  CHECK(contains(sarif.output, "\"uri\": \"defective.body\", \"uriBaseId\": \"%SRCROOT%\""));

  Run stats = bodycheck("--stats defective.body warning.body");
  CHECK(contains(stats.output, "     1  load-joint-type\n"));
  CHECK(contains(stats.output, "     1  yaml-duplicate-key\n"));

  Run list = bodycheck("--list-rules");
  CHECK(list.status == 0);
  CHECK(contains(list.output, "yaml-duplicate-key"));
  CHECK(contains(list.output, "config-invalid"));
}

TEST_CASE("bodycheck: a folder without models is a usage error, not a pass") {
  const std::string empty = std::string(BODYFMT_TEST_DATA_DIR) + "/hostile/mesh_dir.stl";
  Run r = bodycheck("'" + empty + "'");
  CHECK(r.status == 2);
  CHECK(contains(r.output, "error: no model files found"));
}

TEST_CASE("bodycheck: one file named several ways is checked and reported once") {
  const Run once = bodycheck("defective.body");
  const Run thrice = bodycheck("defective.body ./defective.body configured/../defective.body");
  CHECK(thrice.status == once.status);
  CHECK(thrice.output == once.output);
  CHECK(contains(thrice.output, "bodycheck: 1 file checked"));
}

TEST_CASE("bodycheck: --disable takes a comma-separated list, as inline comments do") {
  const Run r = bodycheck("--disable yaml-duplicate-key,load-joint-type --fail-on warning warning.body defective.body");
  CHECK(r.status == 0);
  CHECK(contains(r.output, "2 disabled"));
}

TEST_CASE("bodycheck: -q hides the notes attached to findings too") {
  const Run r = bodycheck("-q defective.body");
  CHECK(contains(r.output, "[load-joint-type]"));
  CHECK(!contains(r.output, "note:"));
}

TEST_CASE("bodycheck: a report that cannot be written says why") {
  const Run r = bodycheck("-o /no/such/folder/report.txt clean.body");
  CHECK(r.status == 2);
  CHECK(contains(r.output, "/no/such/folder/report.txt: cannot write the report: No such file or directory"));
}

TEST_CASE("bodycheck: a misspelt or stale inline suppression is a warning at its rule id") {
  Run r = bodycheck("stale_suppressions.body");
  CHECK(r.status == 1);  // the misspelt suppression did not suppress inertia-triangle
  CHECK(contains(r.output, "stale_suppressions.body:12:14: error: inertia of link"));
  CHECK(contains(r.output, "[inertia-triangle]"));
  CHECK(contains(r.output,
                 "stale_suppressions.body:12:61: warning: this suppression comment names an unknown rule id "
                 "'inertia-triangel'; did you mean 'inertia-triangle'? [suppression-unknown-rule]"));
  CHECK(contains(r.output,
                 "stale_suppressions.body:14:28: warning: '# bodycheck: disable=geometry-invalid-size' "
                 "suppresses nothing on the line it covers [suppression-unused]"));
  CHECK(contains(r.output, "stale_suppressions.body:14:51: warning: '# bodycheck: disable=inertia-com-outside'"));
  // A used suppression is not reported, and --disable of the rule silences the check.
  CHECK(!contains(bodycheck("suppressed.body").output, "suppression-"));
  CHECK(!contains(bodycheck("--disable suppression-unused,suppression-unknown-rule stale_suppressions.body").output,
                  "[suppression-"));
}

TEST_CASE("bodycheck: a binary file given as a model gets one line, not its bytes as a source line") {
  Run r = bodycheck("../hostile/binary_garbage.body");
  CHECK(r.status == 2);
  CHECK(r.output ==
        "../hostile/binary_garbage.body: fatal error: this is a binary file, not YAML text (a NUL byte at byte 7); "
        "a .body model is a YAML text file [yaml-syntax]\n"
        "bodycheck: 1 file checked: 1 error, 0 warnings, 0 notes\n");
  // UTF-16 text with its byte-order mark is text (libyaml transcodes it), not binary.
  CHECK(bodycheck("../hostile/utf16.body").status == 0);
}
