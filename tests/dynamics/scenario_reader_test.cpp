// The scenario reader on inline files: what it takes, and each refusal at its line and column
// (a command after the duration, a negative time, a repeated key, time out of order).
#include <doctest/doctest.h>

#include <bodyfmt/dynamics/scenario.h>
#include <bodyfmt/load.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace bodyfmt;

namespace {

namespace fs = std::filesystem;

struct Read {
  std::optional<dynamics::ScenarioSpec> spec;
  CollectingSink sink;
};

/// Reads `text` as a scenario for examples/scouttank.body.
Read read(const std::string& text) {
  static const std::optional<Model> model = [] {
    CollectingSink sink;
    return load_body(std::string(BODYFMT_EXAMPLES_DIR) + "/scouttank.body", LoadOptions{}, sink);
  }();
  REQUIRE(model);
  const fs::path path = fs::temp_directory_path() / ("scenario_reader_" + std::to_string(getpid()) + ".yaml");
  std::ofstream(path) << text;
  Read r;
  r.spec = dynamics::read_scenario(path.string(), *model, r.sink);
  fs::remove(path);
  return r;
}

/// The scenario error at line:column with a message containing `what`.
bool error_at(const CollectingSink& sink, int line, int column, const std::string& what) {
  for (const Diagnostic& d : sink.diagnostics())
    if (d.rule_id == "dynamics-scenario" && d.severity == Severity::kError && d.location.line == line &&
        d.location.column == column && d.message.find(what) != std::string::npos)
      return true;
  return false;
}

}  // namespace

TEST_CASE("scenario reader: a valid scenario, commands in time order") {
  const Read r = read(
      "duration: 2\nsample: 0.01\ncommands:\n"
      "  - {time: 0, tracks: {BELT_A: 0.5, BELT_B: 0.5}}\n"
      "  - {time: 1.5, joints: {TOWER: {target: 0.2, p: 200, d: 50}}}\n");
  REQUIRE(r.spec);
  CHECK(r.sink.error_count() == 0);
  CHECK(r.spec->duration == 2);
  REQUIRE(r.spec->commands.size() == 2);
  CHECK(r.spec->commands[1].time == 1.5);
  CHECK(r.spec->commands[0].tracks.size() == 2);
}

TEST_CASE("scenario reader: a command after 'duration' is an error at its time") {
  const Read r =
      read("duration: 2\ncommands:\n  - {time: 0.5, tracks: {BELT_A: 1}}\n  - {time: 3, tracks: {BELT_A: 0}}\n");
  CHECK_FALSE(r.spec);
  CHECK(error_at(r.sink, 4, 12, "a command at 3 s comes after 'duration' (2 s) and would never take effect"));
}

TEST_CASE("scenario reader: a negative time says so, not 'out of order'") {
  const Read r = read("duration: 2\ncommands:\n  - {time: -1, tracks: {BELT_A: 1}}\n");
  CHECK_FALSE(r.spec);
  CHECK(error_at(r.sink, 3, 12, "'time' -1 s is negative: a scenario starts at 0 s"));
  for (const Diagnostic& d : r.sink.diagnostics()) CHECK(d.message.find("time order") == std::string::npos);
}

TEST_CASE("scenario reader: a repeated key is an error, not a silent last value") {
  const Read r = read("duration: 2\nduration: 5\n");
  CHECK_FALSE(r.spec);
  CHECK(r.sink.has("yaml-duplicate-key"));
  CHECK(error_at(r.sink, 2, 1, "a key repeated in a scenario is refused"));
}

TEST_CASE("scenario reader: commands out of time order are refused at the later one") {
  const Read r =
      read("duration: 2\ncommands:\n  - {time: 1, tracks: {BELT_A: 1}}\n  - {time: 0.5, tracks: {BELT_A: 0}}\n");
  CHECK_FALSE(r.spec);
  CHECK(error_at(r.sink, 4, 12, "commands must be in time order"));
}
