// Output writers: the text format contract (byte-exact), JSON and SARIF structure.
#include <bodyfmt/report.h>
#include <bodyfmt/rules.h>

#include "text/text_util.h"

#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>
#include <string>

using namespace bodyfmt;

namespace {

/// A scratch file holding `text`, removed at the end of the test.
struct TempFile {
  std::string path;
  explicit TempFile(const std::string& name, const std::string& text) : path(name) {
    std::ofstream(path, std::ios::binary) << text;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

Diagnostic make(std::string file, int line, int column, Severity severity, std::string rule, std::string message) {
  Diagnostic d;
  d.location = {std::move(file), line, column};
  d.severity = severity;
  d.rule_id = std::move(rule);
  d.message = std::move(message);
  return d;
}

int occurrences(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("report: text format with source line, caret, via and hint (golden)") {
  TempFile file("report_text_golden.body", "links:\n  - name: A\n\tjoint_type: hinge\r\n");
  Diagnostic d = make(file.path, 3, 14, Severity::kError, "load-joint-type", "illegal joint type \"hinge\"");
  d.via = SourceLocation{file.path, 1, 1};
  d.fix_hint = "use revolute";
  SourceLines sources;
  sources.add_file(file.path);
  const std::string expected =
      "report_text_golden.body:3:14: error: illegal joint type \"hinge\" [load-joint-type]\n"
      "\tjoint_type: hinge\n"
      "\t            ^\n"
      "report_text_golden.body:1:1: note: reached through this alias\n"
      "report_text_golden.body:3:14: note: use revolute\n";
  CHECK(format_text_diagnostic(d, sources) == expected);
}

TEST_CASE("report: only files added as model text are quoted (issue 45)") {
  TempFile file("report_text_secret.body", "root:$6$secret-hash:19000:0:99999:7:::\n");
  const Diagnostic d = make(file.path, 1, 1, Severity::kError, "load-top-level", "m");
  SourceLines sources;
  CHECK(format_text_diagnostic(d, sources) == "report_text_secret.body:1:1: error: m [load-top-level]\n");
  sources.add_file(file.path);
  CHECK(format_text_diagnostic(d, sources).find("secret-hash") != std::string::npos);
}

TEST_CASE("report: text caret counts UTF-8 characters and tolerates odd positions") {
  TempFile file("report_text_utf8.body", "name: \xC3\xA9t\xC3\xA9 x\n");
  SourceLines sources;
  sources.add_file(file.path);
  // Byte column 12 is the `x` after two 2-byte characters: 9 characters precede it.
  CHECK(format_text_diagnostic(make(file.path, 1, 12, Severity::kWarning, "r", "m"), sources) ==
        "report_text_utf8.body:1:12: warning: m [r]\nname: \xC3\xA9t\xC3\xA9 x\n         ^\n");
  // Past the end of the line: the caret goes there.
  CHECK(format_text_diagnostic(make(file.path, 1, 16, Severity::kNote, "r", "m"), sources) ==
        "report_text_utf8.body:1:16: note: m [r]\nname: \xC3\xA9t\xC3\xA9 x\n             ^\n");
  // No such line, no such file, no column: only the header line.
  CHECK(format_text_diagnostic(make(file.path, 7, 1, Severity::kError, "r", "m"), sources) ==
        "report_text_utf8.body:7:1: error: m [r]\n");
  CHECK(format_text_diagnostic(make("no/such/file.body", 1, 1, Severity::kError, "r", "m"), sources) ==
        "no/such/file.body:1:1: error: m [r]\n");
  CHECK(format_text_diagnostic(make(file.path, 1, 0, Severity::kError, "r", "m"), sources) ==
        "report_text_utf8.body:1: error: m [r]\nname: \xC3\xA9t\xC3\xA9 x\n");
  CHECK(format_text_diagnostic(make(file.path, 1, 3, Severity::kError, "r", "m"), sources, {false, true}) ==
        "report_text_utf8.body:1:3: error: m [r]\n");
}

TEST_CASE("report: text report drops notes on request, summary line counts") {
  Report report;
  report.files = {"a.body", "b.body"};
  report.diagnostics = {make("a.body", 1, 1, Severity::kNote, "n", "a note"),
                        make("a.body", 2, 1, Severity::kWarning, "w", "a warning"),
                        make("b.body", 1, 1, Severity::kFatal, "f", "fatal")};
  report.suppressed = 3;
  SourceLines sources;
  TextOptions quiet;
  quiet.notes = false;
  CHECK(format_text_report(report, sources, quiet) ==
        "a.body:2:1: warning: a warning [w]\nb.body:1:1: fatal error: fatal [f]\n");
  CHECK(occurrences(format_text_report(report, sources), "a note") == 1);
  CHECK(format_summary_line(report) == "bodycheck: 2 files checked: 1 error, 1 warning, 1 note, 3 suppressed\n");
}

TEST_CASE("report: JSON document structure") {
  Report report;
  report.files = {"a.body", "b \"q\".body"};
  Diagnostic d = make("a.body", 4, 9, Severity::kError, "load-joint-type", "illegal \"x\"");
  d.via = SourceLocation{"a.body", 2, 3};
  d.fix_hint = "use revolute";
  report.diagnostics = {d, make("b \"q\".body", 1, 1, Severity::kFatal, "yaml-syntax", "bad")};
  const std::string json = format_json_report(report, ToolInfo{"bodycheck", "1.2.3", ""});
  CHECK(json.find("\"version\": 1,") != std::string::npos);
  CHECK(json.find("\"tool\": {\"name\": \"bodycheck\", \"version\": \"1.2.3\"}") != std::string::npos);
  CHECK(json.find("\"files\": [\n    \"a.body\",\n    \"b \\\"q\\\".body\"\n  ]") != std::string::npos);
  CHECK(json.find("{\"file\": \"a.body\", \"line\": 4, \"column\": 9, \"severity\": \"error\", \"rule\": "
                  "\"load-joint-type\", \"message\": \"illegal \\\"x\\\"\", \"via\": {\"file\": \"a.body\", "
                  "\"line\": 2, \"column\": 3}, \"fix_hint\": \"use revolute\", \"fixes\": []}") != std::string::npos);
  CHECK(json.find("\"severity\": \"fatal\", \"rule\": \"yaml-syntax\", \"message\": \"bad\", \"via\": null, "
                  "\"fix_hint\": null, \"fixes\": []}") != std::string::npos);
  CHECK(json.find("\"summary\": {\"files\": 2, \"fatal\": 1, \"errors\": 1, \"warnings\": 0, \"notes\": 0, "
                  "\"suppressed\": 0, \"disabled\": 0, \"by_rule\": {\"load-joint-type\": 1, \"yaml-syntax\": 1}}") !=
        std::string::npos);
  // Balanced brackets outside strings, and it ends with a newline.
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"')
      in_string = true;
    else if (c == '{' || c == '[')
      ++depth;
    else if (c == '}' || c == ']') {
      --depth;
      CHECK(depth >= 0);
    }
  }
  CHECK(depth == 0);
  CHECK(json.back() == '\n');

  const std::string empty = format_json_report(Report{}, ToolInfo{"bodycheck", "1", ""});
  CHECK(empty.find("\"files\": [],") != std::string::npos);
  CHECK(empty.find("\"diagnostics\": [],") != std::string::npos);
}

TEST_CASE("report: SARIF structure") {
  Report report;
  report.files = {"dir/a file.body", "b.body"};
  Diagnostic d = make("dir/a file.body", 4, 9, Severity::kWarning, "yaml-duplicate-key", "duplicate key \"mass\"");
  d.via = SourceLocation{"b.body", 2, 3};
  d.fix_hint = "remove one";
  report.diagnostics = {d, make("b.body", 1, 1, Severity::kFatal, "yaml-syntax", "bad."),
                        make("b.body", 2, 0, Severity::kNote, "not-a-rule", "")};
  const std::string sarif = format_sarif_report(report, ToolInfo{"bodycheck", "1.2.3", "https://example.org/"});
  CHECK(sarif.find("\"$schema\": \"https://json.schemastore.org/sarif-2.1.0.json\"") != std::string::npos);
  CHECK(sarif.find("\"version\": \"2.1.0\"") != std::string::npos);
  CHECK(occurrences(sarif, "\"tool\": {") == 1);  // one run
  CHECK(sarif.find("\"name\": \"bodycheck\",\n          \"version\": \"1.2.3\",\n          \"informationUri\": "
                   "\"https://example.org/\"") != std::string::npos);
  // Every rule of the table, with its default level; ruleIndex points at the row.
  const auto& rules = all_rules();
  CHECK(occurrences(sarif, "\"defaultConfiguration\"") == static_cast<int>(rules.size()));
  std::size_t dup = 0;
  while (rules[dup].id != "yaml-duplicate-key") ++dup;
  CHECK(sarif.find("{\"id\": \"yaml-duplicate-key\", \"name\": \"YamlDuplicateKey\", \"shortDescription\": {\"text\": "
                   "\"A mapping repeats a key; the last one wins.\"}") != std::string::npos);
  CHECK(sarif.find(
            "\"ruleId\": \"yaml-duplicate-key\", \"ruleIndex\": " + std::to_string(dup) +
            ", \"level\": \"warning\", \"message\": {\"text\": \"Duplicate key \\\"mass\\\". Fix: Remove one.\"}") !=
        std::string::npos);
  // Relative, percent-encoded URIs under %SRCROOT%, with regions and artifact indices.
  CHECK(sarif.find("\"artifactLocation\": {\"uri\": \"dir/a%20file.body\", \"uriBaseId\": \"%SRCROOT%\", "
                   "\"index\": 0}, \"region\": {\"startLine\": 4, \"startColumn\": 9}") != std::string::npos);
  CHECK(sarif.find("\"relatedLocations\": [{\"id\": 1, \"physicalLocation\": {\"artifactLocation\": {\"uri\": "
                   "\"b.body\", \"uriBaseId\": \"%SRCROOT%\", \"index\": 1}, \"region\": {\"startLine\": 2, "
                   "\"startColumn\": 3}}") != std::string::npos);
  CHECK(sarif.find("\"originalUriBaseIds\": {\"%SRCROOT%\": {\"uri\": \"file:///") != std::string::npos);
  // Fatal is an error; the message already ending with a period keeps one; unknown rules
  // have no ruleIndex; an unknown column gives no startColumn.
  CHECK(sarif.find("\"ruleId\": \"yaml-syntax\", \"ruleIndex\": ") != std::string::npos);
  CHECK(sarif.find("\"level\": \"error\", \"message\": {\"text\": \"Bad.\"}") != std::string::npos);
  CHECK(sarif.find("{\"ruleId\": \"not-a-rule\", \"level\": \"note\", \"message\": {\"text\": \".\"}") !=
        std::string::npos);
  CHECK(sarif.find("\"region\": {\"startLine\": 2}") != std::string::npos);
  CHECK(occurrences(sarif, "\"roles\": [\"analysisTarget\"]") == 2);
}

namespace {
std::string caret_text(const std::string& line, int column) {
  SourceLines sources;
  sources.add("x.body", line + "\n");
  Diagnostic d;
  d.severity = Severity::kError;
  d.rule_id = "load-number";
  d.message = "m";
  d.location = {"x.body", 1, column};
  return format_text_diagnostic(d, sources);
}
}  // namespace

TEST_CASE("report: a long source line is shown as a bounded window around the caret") {
  std::string line = "faces: [";
  for (int i = 0; i < 10000; ++i) line += "x, ";
  const int column = static_cast<int>(line.size()) / 2 + 1;  // an 'x' in the middle
  const std::string text = caret_text(line, column);
  CHECK(text.size() < 500);
  const auto lines = bodyfmt::text::split_lines(text);
  REQUIRE(lines.size() == 3);
  CHECK(lines[1].rfind("...", 0) == 0);
  CHECK(lines[1].size() >= 160);
  CHECK(lines[1].substr(lines[1].size() - 3) == "...");
  // The caret stands under the character the column names.
  CHECK(lines[1][lines[2].size() - 1] == line[static_cast<std::size_t>(column - 1)]);
}

TEST_CASE("report: the caret counts two columns for wide characters, control bytes print as '?'") {
  // "名前: X" - two CJK characters (3 bytes, 2 columns each), then ": " and the value.
  const std::string line = "\xE5\x90\x8D\xE5\x89\x8D: X";
  CHECK(caret_text(line, 9) == "x.body:1:9: error: m [load-number]\n" + line + "\n      ^\n");
  CHECK(caret_text("a\x01"
                   "b",
                   3) == "x.body:1:3: error: m [load-number]\na?b\n  ^\n");
}
