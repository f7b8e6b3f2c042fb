// .bodycheck.yaml (tools/common/check_config): discovery and the located errors of a malformed file.
#include "check_config.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

using namespace bodyfmt;
using namespace bodyfmt::tools;

TEST_CASE("policy: config discovery walks up and the nearest config wins") {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / "bodyfmt_policy_config_test";
  fs::remove_all(root);
  fs::create_directories(root / "a" / "b" / "c");
  std::ofstream(root / ".bodycheck.yaml") << "werror: true\n";
  std::ofstream(root / "a" / "b" / ".bodycheck.yaml") << "fail_on: warning\n";
  CHECK(find_config((root / "a" / "b" / "c" / "x.body").string()) == (root / "a" / "b" / ".bodycheck.yaml").string());
  CHECK(find_config((root / "a" / "b" / "x.body").string()) == (root / "a" / "b" / ".bodycheck.yaml").string());
  CHECK(find_config((root / "a" / "x.body").string()) == (root / ".bodycheck.yaml").string());
  fs::remove_all(root);
}

TEST_CASE("policy: config keys and located errors for a malformed config") {
  CollectingSink sink;
  auto config = read_config_string(
      "# comment\ndisable: [units-*, yaml-duplicate-key]\nenable: load-info-key\nfail_on: warning\nwerror: yes\n",
      "c.yaml", sink);
  REQUIRE(config);
  CHECK(sink.diagnostics().empty());
  CHECK(config->disable == std::vector<std::string>{"units-*", "yaml-duplicate-key"});
  CHECK(config->enable == std::vector<std::string>{"load-info-key"});
  CHECK(config->fail_on == Severity::kWarning);
  CHECK(config->werror == true);

  CHECK(read_config_string("", "c.yaml", sink));  // empty is fine

  auto expect_error = [](const std::string& text, int line, int column, const std::string& fragment) {
    CollectingSink errors;
    CHECK(!read_config_string(text, "c.yaml", errors));
    REQUIRE(errors.diagnostics().size() == 1);
    const Diagnostic& d = errors.diagnostics()[0];
    CHECK(d.rule_id == "config-invalid");
    CHECK(d.severity == Severity::kError);
    CHECK(d.location == SourceLocation{"c.yaml", line, column});
    CHECK(d.message.find(fragment) != std::string::npos);
  };
  expect_error("disable: [yaml-duplicat-key]\n", 1, 11, "did you mean 'yaml-duplicate-key'");
  expect_error("fail_on: sometimes\n", 1, 10, "'fail_on' must be");
  expect_error("werror: maybe\n", 1, 9, "'werror' must be");
  expect_error("# x\ndisabled: [a]\n", 2, 1, "unknown key 'disabled'");
  expect_error("disable: {a: 1}\n", 1, 10, "list of rule ids");
  expect_error("- a\n", 1, 1, "must be a mapping");
  expect_error("disable: [a\n", 2, 1, "malformed YAML");
}
