// Every corpus model through load, derive and check: the (model, rule, count) of each
// warning and error must equal tests/corpus/bodycheck_expected.txt, so a finding that appears
// or disappears fails. Set BODYFMT_WRITE_BODYCHECK_EXPECTED=<path> to write the actual table.

#include "support/load_helpers.h"
#include "unit/validate/validate_support.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using bodyfmt::Severity;

namespace {

std::string actual_table(std::string& details) {
  const fs::path root = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid";
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.is_regular_file() && entry.path().extension() == ".body") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::ostringstream out;
  for (const fs::path& file : files) {
    const std::string model = fs::relative(file, root).generic_string();
    auto result = bodyfmt::test::check_file(file.string());
    std::map<std::string, int> counts;
    for (const bodyfmt::Diagnostic& d : result.diagnostics) {
      if (d.severity == Severity::kNote) continue;
      ++counts[d.rule_id];
      details += model + ": " + bodyfmt::format_diagnostic(d) + "\n";
    }
    if (!result.loaded) counts["<not loaded>"] = 1;
    for (const auto& [rule, n] : counts) out << model << '\t' << rule << '\t' << n << '\n';
  }
  return out.str();
}

std::string read_expected(const fs::path& path) {
  std::ifstream in(path);
  std::string line, out;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') out += line + "\n";
  return out;
}

}  // namespace

TEST_CASE("validate: corpus findings match tests/corpus/bodycheck_expected.txt") {
  const fs::path corpus = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid";
  if (!fs::exists(corpus)) {
    MESSAGE("shared corpus missing at " << corpus.string());
    return;
  }
  std::string details;
  const std::string actual = actual_table(details);
  if (const char* path = std::getenv("BODYFMT_WRITE_BODYCHECK_EXPECTED")) {
    std::ofstream(path) << actual;
    std::ofstream(std::string(path) + ".details") << details;
  }
  const fs::path expected_path = fs::path(BODYFMT_TEST_DATA_DIR) / ".." / "corpus" / "bodycheck_expected.txt";
  const std::string expected = read_expected(expected_path);
  // Report line by line, so that a failure names exactly what appeared or disappeared.
  std::istringstream a(actual), e(expected);
  std::vector<std::string> al, el, appeared, disappeared;
  for (std::string l; std::getline(a, l);) al.push_back(l);
  for (std::string l; std::getline(e, l);) el.push_back(l);
  std::sort(al.begin(), al.end());
  std::sort(el.begin(), el.end());
  std::set_difference(al.begin(), al.end(), el.begin(), el.end(), std::back_inserter(appeared));
  std::set_difference(el.begin(), el.end(), al.begin(), al.end(), std::back_inserter(disappeared));
  for (const std::string& l : appeared) FAIL_CHECK("new finding (model, rule, count): " << l);
  for (const std::string& l : disappeared) FAIL_CHECK("finding gone or count changed: " << l);
}
