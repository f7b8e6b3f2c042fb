// `bodysim run --scenario` reads the scenario with the model loader's bounded reader (issue 26,
// item 4): a device or a FIFO is refused before anything is read, located at the path, with
// exit 2. Before, /dev/zero was read until bad_alloc (past 2 GB) and a FIFO with no writer
// blocked forever; `timeout` turns either into a failure here rather than a hung test.
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

struct Refusal {
  int status = -1;
  std::string stderr_text;
  double seconds = 0;
};

/// `bodysim run` on examples/scouttank.body with `scenario`, at most 20 s.
Refusal run_with_scenario(const std::string& scenario, const fs::path& csv) {
  const fs::path err = fs::temp_directory_path() / ("bodysim_scenario_input_" + std::to_string(getpid()) + ".txt");
  const std::string command = std::string("timeout 20 '") + BODYFMT_BODYSIM + "' run '" + BODYFMT_EXAMPLES_DIR +
                              "/scouttank.body' --scenario '" + scenario + "' --csv '" + csv.string() + "' 2>'" +
                              err.string() + "' >/dev/null";
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system(command.c_str());
  Refusal r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  r.stderr_text = text.str();
  in.close();
  fs::remove(err);
  return r;
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

}  // namespace

TEST_CASE("bodysim: run refuses --scenario /dev/zero at once, located, exit 2, nothing written") {
  const fs::path csv = fs::temp_directory_path() / ("bodysim_dev_zero_" + std::to_string(getpid()) + ".csv");
  fs::remove(csv);
  const Refusal r = run_with_scenario("/dev/zero", csv);
  INFO(r.stderr_text);
  CHECK(r.status == 2);  // 124 would be the timeout
  CHECK(
      contains(r.stderr_text, "/dev/zero: fatal error: cannot read the scenario \"/dev/zero\": is not a regular file"));
  CHECK(contains(r.stderr_text, "[io-read]"));
  CHECK(contains(r.stderr_text, "nothing was simulated: the scenario cannot be read"));
  CHECK(r.seconds < 10);
  CHECK(!fs::exists(csv));
}

TEST_CASE("bodysim: run refuses a FIFO scenario with no writer instead of blocking, exit 2") {
  const fs::path dir = fs::temp_directory_path() / ("bodysim_fifo_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path fifo = dir / "scenario.yaml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const Refusal r = run_with_scenario(fifo.string(), dir / "out.csv");
  INFO(r.stderr_text);
  CHECK(r.status == 2);
  CHECK(contains(r.stderr_text, "scenario.yaml: fatal error: cannot read the scenario \"" + fifo.string() +
                                    "\": is not a regular file (a device, a FIFO or a socket) [io-read]"));
  CHECK(r.seconds < 10);
  CHECK(!fs::exists(dir / "out.csv"));
  fs::remove_all(dir);
}

TEST_CASE("bodysim: run refuses a folder or a missing file as the scenario, saying why") {
  const fs::path csv = fs::temp_directory_path() / ("bodysim_no_scenario_" + std::to_string(getpid()) + ".csv");
  const fs::path dir = fs::temp_directory_path();
  Refusal r = run_with_scenario(dir.string(), csv);
  CHECK(r.status == 2);
  CHECK(contains(r.stderr_text, "cannot read the scenario \"" + dir.string() + "\": is a directory, not a file"));
  r = run_with_scenario((dir / "no_such_scenario.yaml").string(), csv);
  CHECK(r.status == 2);
  CHECK(contains(r.stderr_text, "no_such_scenario.yaml\": no such file [io-read]"));
  CHECK(!fs::exists(csv));
}
