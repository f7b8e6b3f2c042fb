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

TEST_CASE("validate: every rule id literal in the sources is in the rule table") {
  // A string literal that looks like a rule id: a family prefix, a dash, kebab-case.
  const std::regex id_literal(
      R"re("((yaml|load|units|structure|geometry|device|resource|subbody|extra-joint|mesh|io|internal|inertia|joint)-[a-z0-9.-]+)")re");
  std::set<std::string> unknown;
  int files = 0, ids = 0;
  for (const char* dir : {"libbodyfmt/src", "validate", "converters"}) {
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
        ++ids;
        if (!bodyfmt::find_rule(id)) unknown.insert(entry.path().lexically_relative(kSourceDir).string() + ": " + id);
      }
    }
  }
  CHECK(files > 20);
  CHECK(ids > 50);
  for (const std::string& u : unknown) FAIL_CHECK("rule id not in rule_table.cpp: " << u);
}
