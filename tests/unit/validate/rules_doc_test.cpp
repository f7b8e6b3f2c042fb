// docs/rules.md is generated from the rule table (rules_doc); these tests keep the committed
// file, the table and the rule ids used in the sources from drifting apart.

#include <bodyfmt/rules.h>
#include <bodyfmt/validate.h>

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

const fs::path kSourceDir = fs::path(BODYFMT_EXAMPLES_DIR).parent_path();

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

}  // namespace

TEST_CASE("validate: docs/rules.md equals the rule table (regenerate with rules_doc)") {
  const fs::path doc = kSourceDir / "docs" / "rules.md";
  REQUIRE(fs::exists(doc));
  CHECK_MESSAGE(read(doc) == bodyfmt::validate::rules_markdown(),
                "docs/rules.md is stale: run ./build/rules_doc > docs/rules.md");
}

TEST_CASE("validate: every rule of the table is documented with a summary and rationale") {
  const std::string markdown = bodyfmt::validate::rules_markdown();
  for (const bodyfmt::RuleInfo& rule : bodyfmt::all_rules()) {
    CAPTURE(rule.id);
    CHECK(markdown.find("| `" + std::string(rule.id) + "` |") != std::string::npos);
    CHECK(!rule.summary.empty());
    CHECK(!rule.rationale.empty());
  }
}

/// Every family prefix of the table (the text before the first '-'), as a regex alternative.
std::string family_alternatives() {
  std::set<std::string> families;
  for (const bodyfmt::RuleInfo& rule : bodyfmt::all_rules())
    families.insert(std::string(rule.id.substr(0, rule.id.find('-'))));
  std::string alternatives;
  for (const std::string& f : families) alternatives += (alternatives.empty() ? "" : "|") + f;
  return alternatives;
}

/// "extra-joint" or "extra-joint-": a family's name, as docs/rules.md groups the rules.
bool is_family_label(const std::string& text) {
  const std::string prefix = text.back() == '-' ? text : text + "-";
  for (const bodyfmt::RuleInfo& rule : bodyfmt::all_rules())
    if (rule.id.rfind(prefix, 0) == 0 && rule.id != text) return !bodyfmt::find_rule(text);
  return false;
}

const char* const kSourceFolders[] = {"libbodyfmt/src", "validate", "converters", "tools"};

TEST_CASE("validate: every rule id literal in the sources is in the rule table") {
  // A string literal that looks like a rule id: a family prefix of the table, a dash, kebab-case.
  const std::string families = family_alternatives();
  CHECK(families.find("export") != std::string::npos);
  CHECK(families.find("config") != std::string::npos);
  const std::regex id_literal("\"((" + families + ")-[a-z0-9.-]+)\"");
  std::set<std::string> unknown;
  int files = 0, ids = 0;
  for (const char* dir : kSourceFolders) {
    const fs::path root = kSourceDir / dir;
    if (!fs::exists(root)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
      ++files;
      const std::string text = read(entry.path());
      for (auto it = std::sregex_iterator(text.begin(), text.end(), id_literal); it != std::sregex_iterator(); ++it) {
        const std::string id = (*it)[1];
        // File names and URLs in comments or messages are not ids: ids never end in a dot
        // followed by an extension-like suffix such as ".body".
        if (id.find(".body") != std::string::npos || id.find(".cpp") != std::string::npos) continue;
        if (is_family_label(id)) continue;
        ++ids;
        if (!bodyfmt::find_rule(id)) unknown.insert(entry.path().lexically_relative(kSourceDir).string() + ": " + id);
      }
    }
  }
  CHECK(files > 20);
  CHECK(ids > 50);
  for (const std::string& u : unknown)
    FAIL_CHECK("rule id not in the rule table (libbodyfmt/src/diagnostic/rules.cpp): " << u);
}

TEST_CASE("validate: diagnostics are made in one place, with the rule table's severity") {
  // make_diagnostic (rules.cpp) is the only code that sets a severity on a new Diagnostic;
  // DiagnosticPolicy (diagnostic_policy.cpp) is the only code that changes one.
  const std::regex sets_severity(R"(\.severity\s*=\s*[^=])");
  std::set<std::string> offenders;
  for (const char* dir : kSourceFolders) {
    const fs::path root = kSourceDir / dir;
    if (!fs::exists(root)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      const std::string name = entry.path().filename().string();
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
      if (name == "rules.cpp" || name == "diagnostic_policy.cpp") continue;
      const std::string text = read(entry.path());
      if (std::regex_search(text, sets_severity))
        offenders.insert(entry.path().lexically_relative(kSourceDir).string());
    }
  }
  for (const std::string& o : offenders) FAIL_CHECK("builds a Diagnostic by hand instead of make_diagnostic: " << o);
}
