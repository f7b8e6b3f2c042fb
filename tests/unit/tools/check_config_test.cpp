// .bodycheck.yaml (tools/common/check_config): discovery and the located errors of a malformed file.
#include "check_config.h"

#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

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
  expect_error("# x\ndisabled: [a]\n", 2, 1, "unknown key 'disabled' in .bodycheck.yaml; did you mean 'disable'?");
  expect_error("failon: error\n", 1, 1, "did you mean 'fail_on'?");
  expect_error("strict: true\n", 1, 1, "unknown key 'strict' in .bodycheck.yaml");
  expect_error("disable: {a: 1}\n", 1, 10, "list of rule ids");
  expect_error("- a\n", 1, 1, "must be a mapping");
  expect_error("disable: [a\n", 2, 1, "malformed YAML");
}

TEST_CASE("policy: a config that is not a regular file is refused before it is read") {
  // The model loader's bounded reader: /dev/zero was read without end, a FIFO blocked.
  namespace fs = std::filesystem;
  const fs::path fifo = fs::temp_directory_path() / ("bodyfmt_config_fifo_" + std::to_string(getpid()));
  fs::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const std::string& path : {std::string("/dev/zero"), fifo.string()}) {
    CollectingSink sink;
    CHECK(!read_config(path, sink));
    REQUIRE(sink.diagnostics().size() == 1);
    const Diagnostic& d = sink.diagnostics()[0];
    CHECK(d.rule_id == "io-read");
    CHECK(d.location == SourceLocation{path, 0, 0});
    CHECK(d.message == "cannot read the configuration file: is not a regular file (a device, a FIFO or a socket)");
  }
  fs::remove(fifo);
  CollectingSink missing;
  CHECK(!read_config("no/such/.bodycheck.yaml", missing));
  REQUIRE(missing.diagnostics().size() == 1);
  CHECK(missing.diagnostics()[0].message == "cannot read the configuration file: no such file");
}

TEST_CASE("policy: severity in a config raises or lowers rules, located errors for a bad id or level") {
  CollectingSink sink;
  auto config = read_config_string("severity: {yaml-duplicate-key: error, inertia-*: note}\n", "c.yaml", sink);
  REQUIRE(config);
  CHECK(sink.diagnostics().empty());
  REQUIRE(config->severity.size() == 2);
  CHECK(config->severity[0] == std::pair<std::string, Severity>{"yaml-duplicate-key", Severity::kError});
  CHECK(config->severity[1] == std::pair<std::string, Severity>{"inertia-*", Severity::kNote});

  auto expect_error = [](const std::string& text, int line, int column, const std::string& fragment) {
    CollectingSink errors;
    CHECK(!read_config_string(text, "c.yaml", errors));
    REQUIRE(errors.diagnostics().size() == 1);
    const Diagnostic& d = errors.diagnostics()[0];
    CHECK(d.rule_id == "config-invalid");
    CHECK(d.location == SourceLocation{"c.yaml", line, column});
    CHECK(d.message.find(fragment) != std::string::npos);
  };
  expect_error("severity: {yaml-duplicat-key: error}\n", 1, 12, "did you mean 'yaml-duplicate-key'");
  expect_error("severity: {yaml-duplicate-key: fatal}\n", 1, 32, "must be note, warning or error");
  expect_error("severity: [yaml-duplicate-key]\n", 1, 11, "'severity' must be a mapping");
  expect_error("severty: {}\n", 1, 1, "did you mean 'severity'?");
}
