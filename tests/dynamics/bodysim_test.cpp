// The bodysim command line: check-tank on SimpleTank (refused as written, passing with
// --balance-inertia) and on examples/scouttank.body, the exit-code contract, and `run`.
#include <doctest/doctest.h>

#include <unistd.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Run {
  int status = -1;
  std::string out;  // stdout
  std::string all;  // stdout, then stderr
};

Run bodysim(const std::string& args) {
  // One file per test process: ctest -j runs these cases side by side, and a shared file let
  // one case read another's stderr (a sanitizer CI run lost [dynamics-inertia-balanced] so).
  const std::filesystem::path err =
      std::filesystem::temp_directory_path() / ("bodysim_test_stderr_" + std::to_string(getpid()) + ".txt");
  const std::string command = std::string("'") + BODYFMT_BODYSIM + "' " + args + " 2>'" + err.string() + "'";
  Run run;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) run.out.append(buffer, n);
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  run.all = run.out + text.str();
  in.close();
  std::filesystem::remove(err);
  return run;
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

const std::string kSimpleTank = std::string(BODYFMT_SHARED_DIR) + "/corpus/choreonoid/Tank/SimpleTank.body";
const std::string kScoutTank = std::string(BODYFMT_EXAMPLES_DIR) + "/scouttank.body";

}  // namespace

TEST_CASE("bodysim: check-tank refuses SimpleTank as written, naming the chassis inertia finding (exit 2)") {
  const Run r = bodysim("check-tank '" + kSimpleTank + "'");
  CHECK(r.status == 2);
  CHECK(contains(r.all, "SimpleTank.body:12:14: error: principal moments (0.1, 0.1, 0.5) of link \"CHASSIS\""));
  CHECK(contains(r.all, "[inertia-triangle]"));
  CHECK(contains(r.all, "--balance-inertia"));
  CHECK(!contains(r.out, "PASS"));
}

TEST_CASE("bodysim: check-tank passes every check on SimpleTank with --balance-inertia (exit 0)") {
  const Run r = bodysim("check-tank --balance-inertia '" + kSimpleTank + "'");
  INFO(r.all);
  CHECK(r.status == 0);
  CHECK(contains(r.all, "[dynamics-inertia-balanced]"));
  CHECK(contains(r.out, "tracks: left \"TRACK_L\", right \"TRACK_R\" (found by position), spacing B = 0.4 m"));
  CHECK(!contains(r.out, "FAIL"));
  CHECK(contains(r.out, "33 of 33 checks passed, 0 failed, 0 skipped"));
}

TEST_CASE("bodysim: an asymmetric inertia is refused as bodycheck refuses it, or simulated symmetrised on request") {
  const std::string model = std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/asymmetric_inertia.body";
  Run r = bodysim("check -q '" + model + "'");
  CHECK(r.status == 2);
  CHECK(contains(r.all, "asymmetric_inertia.body:17:9: error: inertia of link \"BODY\" is not symmetric"));
  CHECK(contains(r.all, "[inertia-asymmetric]"));
  r = bodysim("check -q --balance-inertia '" + model + "'");
  INFO(r.all);
  CHECK(r.status == 0);
  CHECK(contains(r.all, "asymmetric_inertia.body:17:9: warning: inertia of link \"BODY\" is not symmetric"));
  CHECK(contains(r.all, "the mean of each off-diagonal pair"));
  CHECK(contains(r.all, "[dynamics-inertia-balanced]"));
  CHECK(!contains(r.all, "[inertia-asymmetric]"));
  CHECK(!contains(r.out, "FAIL"));
}

TEST_CASE("bodysim: a model refused for one error is told every error bodycheck finds in it") {
  // The triangle violation is left to Simulation::build, which the asymmetric tensor keeps from
  // running: it was never said.
  const std::string model = std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/two_inertia_errors.body";
  const Run r = bodysim("check -q '" + model + "'");
  INFO(r.all);
  CHECK(r.status == 2);
  CHECK(contains(r.all, "two_inertia_errors.body:16:9: error: inertia of link \"BODY\" is not symmetric"));
  CHECK(contains(r.all,
                 "two_inertia_errors.body:29:9: error: inertia of link \"ARM\" is impossible for a rigid "
                 "body: principal moments (0.01, 0.01, 0.05)"));
  CHECK(contains(r.all, "[inertia-triangle]"));
}

TEST_CASE("bodysim: check-tank passes every check on examples/scouttank.body (exit 0)") {
  const Run r = bodysim("check-tank '" + kScoutTank + "'");
  INFO(r.all);
  CHECK(r.status == 0);
  // Left and right by position: BELT_B (y = +0.31) is left although listed second.
  CHECK(contains(r.out, "tracks: left \"BELT_B\", right \"BELT_A\" (found by position), spacing B = 0.62 m"));
  CHECK(contains(r.out, "33 of 33 checks passed, 0 failed, 0 skipped"));
}

TEST_CASE("bodysim: a failing check exits 1") {
  // A pitch P gain of 1 N·m/rad cannot hold the cannon: the gravity torque (2.5 kg · g ·
  // 0.25 m ≈ 6.1 N·m) would sag it to about 1.35 rad, far beyond its 5° stop, so the measured
  // sag (at the stop) differs from the servo's equilibrium and the check fails.
  const Run r = bodysim("check-tank --p-gain 1 '" + kScoutTank + "'");
  CHECK(r.status == 1);
  CHECK(contains(r.out, "FAIL  turret: pitch sag under gravity"));
}

TEST_CASE("bodysim: usage errors exit 2") {
  CHECK(bodysim("").status == 2);
  CHECK(bodysim("frobnicate x.body").status == 2);
  CHECK(bodysim("check-tank").status == 2);
  const Run arm = bodysim("check-tank '" + std::string(BODYFMT_EXAMPLES_DIR) + "/arm.body'");
  CHECK(arm.status == 2);
  CHECK(contains(arm.all, "the tank suite needs a free root link"));
}

TEST_CASE("bodysim: one command line with three subcommands, help, version and usage errors said") {
  const Run help = bodysim("--help");
  CHECK(help.status == 0);
  CHECK(contains(help.out, "Usage: bodysim [OPTIONS] SUBCOMMAND"));
  for (const char* sub : {"check-tank", "check", "run"}) {
    CAPTURE(sub);
    CHECK(contains(help.out, std::string("\n  ") + sub + " "));
    const Run sub_help = bodysim(std::string(sub) + " --help");
    CHECK(sub_help.status == 0);
    CHECK(contains(sub_help.out, std::string("Usage: bodysim ") + sub + " [OPTIONS] file"));
    // The front's options and the simulation's in every subcommand.
    CHECK(contains(sub_help.out, "--no-config"));
    CHECK(contains(sub_help.out, "--balance-inertia"));
    CHECK(contains(sub_help.out, "--max-links"));
    // Each subcommand's own options, and not another's.
    CHECK(contains(sub_help.out, "--cross-check") == (std::string(sub) != "run"));
    CHECK(contains(sub_help.out, "--p-gain") == (std::string(sub) == "check-tank"));
    CHECK(contains(sub_help.out, "--scenario") == (std::string(sub) == "run"));
    CHECK(!contains(sub_help.out, "Run `bodysim SUBCOMMAND --help`"));  // the top footer is not inherited
  }
  const Run version = bodysim("--version");
  CHECK(version.status == 0);
  CHECK(version.out.rfind("bodysim ", 0) == 0);
  CHECK(version.out.find_first_of("0123456789") == 8);

  const Run none = bodysim("");
  CHECK(none.status == 2);
  CHECK(contains(none.all, "bodysim: error: a subcommand is required (check-tank, check or run)"));
  CHECK(contains(none.all, "Subcommands:"));
  const Run unknown = bodysim("frobnicate x.body");
  CHECK(unknown.status == 2);
  CHECK(contains(unknown.all, "bodysim: error: unknown subcommand \"frobnicate\" (check-tank, check or run)"));
  const Run bad_option = bodysim("check --no-such-option x.body");
  CHECK(bad_option.status == 2);
  CHECK(contains(bad_option.all, "--no-such-option"));
  const Run foreign_option = bodysim("check --p-gain=3 x.body");  // check-tank's, not check's
  CHECK(foreign_option.status == 2);
  CHECK(contains(foreign_option.all, "--p-gain"));
  const Run no_file = bodysim("run --scenario s.yaml --csv out.csv");
  CHECK(no_file.status == 2);
  CHECK(contains(no_file.all, "file is required"));
  const Run bad_value = bodysim("check-tank --p-gain=-1 x.body");
  CHECK(bad_value.status == 2);
  CHECK(contains(bad_value.all, "--p-gain: must be a number above 0, not -1"));
  CHECK(!contains(bad_value.out, "PASS"));
  const Run negative = bodysim("check-tank --d-gain=-0.5 x.body");
  CHECK(negative.status == 2);
  CHECK(contains(negative.all, "--d-gain: must be a number ≥ 0, not -0.5"));
  const Run zero_gain = bodysim("check-tank --d-gain=0 no_such_model.body");  // 0 is a valid D gain
  CHECK(!contains(zero_gain.all, "--d-gain"));
  CHECK(contains(zero_gain.all, "no_such_model.body"));
  const Run zero = bodysim("run --max-duration 0 --scenario s.yaml --csv out.csv x.body");
  CHECK(zero.status == 2);
  CHECK(contains(zero.all, "--max-duration: must be a number above 0, not 0"));
}

TEST_CASE("bodysim: a model over --max-links is refused at its first link over the limit, before any work") {
  // A 6-link chain, one line per link: with --max-links 4, link 5 (L4: line 9, its name at column
  // 12) is the first over.
  const std::filesystem::path model = std::filesystem::temp_directory_path() / "bodysim_test_chain.body";
  {
    std::ofstream out(model);
    out << "format: ChoreonoidBody\nformat_version: 2.0\nname: Chain\nlinks:\n"
           "  - {name: L0, joint_type: free, mass: 1, inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]}\n";
    for (int i = 1; i < 6; ++i)
      out << "  - {name: L" << i << ", parent: L" << i - 1
          << ", joint_type: revolute, joint_axis: Z, joint_id: " << i - 1
          << ", translation: [0.1, 0, 0], mass: 1, inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]}\n";
  }
  const Run over = bodysim("check --max-links 4 '" + model.string() + "'");
  CHECK(over.status == 2);
  CHECK(contains(over.all,
                 "bodysim_test_chain.body:9:12: fatal error: the model has 6 links, more than bodysim "
                 "simulates (--max-links 4); this is link 5, the first over the limit [dynamics-model-size]"));
  CHECK(contains(over.all, "nothing was simulated"));
  CHECK(bodysim("check --max-links 0 '" + model.string() + "'").status == 2);  // a usage error
  std::filesystem::remove(model);
}

TEST_CASE("bodysim: run writes the scenario's trajectory as CSV") {
  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "bodysim_test_run.csv";
  std::filesystem::remove(csv);
  const Run r =
      bodysim("run --balance-inertia '" + std::string(BODYFMT_EXAMPLES_DIR) + "/simpletank.body' --scenario '" +
              BODYFMT_EXAMPLES_DIR + "/tank_drive.scenario.yaml' --csv '" + csv.string() + "'");
  INFO(r.all);
  REQUIRE(r.status == 0);
  std::ifstream in(csv);
  std::string header, line, row_at_2_49;
  std::getline(in, header);
  CHECK(header.rfind("time,x,y,z,qw,qx,qy,qz,wx,wy,wz,vx,vy,vz,q:TURRET_Y,dq:TURRET_Y,q:TURRET_P,dq:TURRET_P,", 0) ==
        0);
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    if (line.rfind("2.490000,", 0) == 0) row_at_2_49 = line;
  }
  CHECK(rows == 401);  // t = 0 .. 4 s every 10 ms
  REQUIRE(!row_at_2_49.empty());
  std::vector<double> v;
  std::stringstream fields(row_at_2_49);
  for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
  // 2 s after both tracks were set to 1 m/s: moving at 1 m/s along +x (Choreonoid's
  // "1.0 → forward at 1.0 m/s"); the pitch servo holds 0.3 rad less the gravity sag
  // m·g·r/P = 4 · 9.80665 · 0.05 / 200 ≈ 0.0098 rad.
  CHECK(v[11] == doctest::Approx(1.0).epsilon(0.01));
  CHECK(std::abs(v[12]) < 0.01);
  CHECK(v[16] == doctest::Approx(0.3 - 0.0098 * std::cos(0.3)).epsilon(0.01));
}

TEST_CASE("bodysim: run refuses a scenario naming an unknown link, located, and writes nothing") {
  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "bodysim_test_refused.csv";
  std::filesystem::remove(csv);
  const std::string scenario = std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/unknown_link.scenario.yaml";
  const Run r = bodysim("run '" + kScoutTank + "' --scenario '" + scenario + "' --csv '" + csv.string() + "'");
  CHECK(r.status == 2);
  CHECK(contains(r.all,
                 "unknown_link.scenario.yaml:5:14: error: the model has no link \"TRACK_LEFT\" [dynamics-scenario]"));
  CHECK(!std::filesystem::exists(csv));
}

TEST_CASE("bodysim: run --csv never writes over the model, the scenario or a file linked to one (exit 2)") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("bodysim_test_csv_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(std::string(BODYFMT_EXAMPLES_DIR) + "/scouttank.body", dir / "tank.body");
  std::ofstream(dir / "s.yaml") << "duration: 0.02\nsample: 0.01\n";
  fs::create_symlink("tank.body", dir / "link.csv");
  const auto read = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  };
  const std::string model = read(dir / "tank.body");
  for (const auto& entry :
       std::vector<std::pair<std::string, std::string>>{{"tank.body", "it is the model of this run ('"},
                                                        {"link.csv", "it is the model of this run ('"},
                                                        {"s.yaml", "it is the scenario of this run ('"}}) {
    const std::string& csv = entry.first;  // not a structured binding: CAPTURE's lambda takes it
    const std::string& why = entry.second;
    CAPTURE(csv);
    const Run r = bodysim("run '" + (dir / "tank.body").string() + "' --scenario '" + (dir / "s.yaml").string() +
                          "' --csv '" + (dir / csv).string() + "'");
    CHECK(r.status == 2);
    CHECK(contains(r.all, "cannot write '" + (dir / csv).string() + "': " + why));
  }
  CHECK(read(dir / "tank.body") == model);
  CHECK(read(dir / "s.yaml") == "duration: 0.02\nsample: 0.01\n");
  CHECK(fs::is_symlink(dir / "link.csv"));
  fs::remove_all(dir);
}

TEST_CASE("bodysim: run refuses scenarios that would not finish, each value located, before any work") {
  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "bodysim_test_never.csv";
  std::filesystem::remove(csv);
  const std::string data = std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/";
  Run r = bodysim("run '" + kScoutTank + "' --scenario '" + data + "never_finishes.scenario.yaml' --csv '" +
                  csv.string() + "'");
  CHECK(r.status == 2);
  CHECK(contains(r.all,
                 "never_finishes.scenario.yaml:2:11: error: 'duration' 1e+12 s is more than bodysim simulates "
                 "(--max-duration 600 s) [dynamics-scenario]"));
  CHECK(contains(r.all, "never_finishes.scenario.yaml:6:36: error: the gain 'p' -1e+06 is negative"));
  CHECK(contains(r.all, "never_finishes.scenario.yaml:6:45: error: the gain 'd' -5 is negative"));
  CHECK(!std::filesystem::exists(csv));
  r = bodysim("run '" + kScoutTank + "' --scenario '" + data + "long_sample.scenario.yaml' --csv '" + csv.string() +
              "'");
  CHECK(r.status == 2);
  CHECK(contains(r.all, "long_sample.scenario.yaml:2:11: error: 'duration' 10000 s is more than bodysim simulates"));
  // The limits are options: 10000 s in one row passes --max-duration, and --max-rows 0.5 refuses it.
  r = bodysim("run '" + kScoutTank + "' --scenario '" + data + "long_sample.scenario.yaml' --max-duration 1e4 " +
              "--max-rows 0.5 --csv '" + csv.string() + "'");
  CHECK(r.status == 2);
  CHECK(contains(r.all,
                 "long_sample.scenario.yaml:3:9: error: 'duration' / 'sample' gives 1 rows, more than "
                 "--max-rows 0.5 [dynamics-scenario]"));
  // Commands over --max-commands: the first one over the limit is named.
  const std::filesystem::path many = std::filesystem::temp_directory_path() / "bodysim_test_many.scenario.yaml";
  {
    std::ofstream out(many);
    out << "duration: 0.01\ncommands:\n";
    for (int i = 0; i < 12; ++i) out << "  - {time: 0, joints: {TOWER: {target: 0.1, p: 10}}}\n";
  }
  r = bodysim("run '" + kScoutTank + "' --scenario '" + many.string() + "' --max-commands 10 --csv '" + csv.string() +
              "'");
  CHECK(r.status == 2);
  CHECK(contains(r.all,
                 "bodysim_test_many.scenario.yaml:13:5: error: the scenario has 12 commands, more than "
                 "--max-commands 10; this is the first over the limit [dynamics-scenario]"));
  r = bodysim("run '" + kScoutTank + "' --scenario '" + many.string() + "' --csv '" + csv.string() + "'");
  CHECK(r.status == 0);
  std::filesystem::remove(many);
  std::filesystem::remove(csv);
}

TEST_CASE("bodysim check drops a model from its initial pose, joints at their initial displacements") {
  // locked_displaced.body's leg starts at 90 deg, lying beside the body: the model is the
  // body's 0.1 m box high. At the zero pose the leg would hang 0.3 m down, the drop would start
  // 27 cm up instead of 2 cm, and the model would be 0.35 m high. The settle bound is
  // 1e-4 · m · g · h with m = 2.2 kg.
  const std::string model = std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/locked_displaced.body";
  const Run r = bodysim("check -q '" + model + "'");
  CHECK(r.status == 0);
  const std::string line = "drop 2 cm, joints locked: kinetic energy at 3 s [G5]\n";
  const std::size_t at = r.out.find(line);
  REQUIRE(at != std::string::npos);
  // The values are on the line below the check's name.
  const std::size_t values = at + line.size();
  const std::string row = r.out.substr(values, r.out.find('\n', values) - values);
  const std::size_t expected_at = row.find("expected");
  REQUIRE(expected_at != std::string::npos);
  const double expected = std::stod(row.substr(expected_at + 8));
  CHECK(expected == doctest::Approx(1e-4 * 2.2 * 9.80665 * 0.1).epsilon(1e-4));
}

TEST_CASE("bodysim: commands denser in time than the step budget are refused, or stopped, at a command") {
  // Each distinct command time restarts the integrator. 1,000 of them in 0.1 s: over a budget of
  // 900 steps per second they are refused before any work, at the first command over it; under
  // 1,200 they run, and the budget stops the run at the commands, not at a stiff contact.
  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "bodysim_test_dense.csv";
  const std::filesystem::path dense = std::filesystem::temp_directory_path() / "bodysim_test_dense.scenario.yaml";
  std::filesystem::remove(csv);
  {
    std::ofstream out(dense);
    out << "duration: 0.5\ncommands:\n";
    for (int i = 1; i <= 1000; ++i) out << "  - {time: " << i * 1e-4 << ", joints: {TOWER: {target: 0.1, p: 10}}}\n";
  }
  const std::string run = "run '" + kScoutTank + "' --scenario '" + dense.string() + "' --csv '" + csv.string() + "'";
  Run r = bodysim(run + " --max-steps-per-second 900");
  CHECK(r.status == 2);
  CHECK(contains(r.all,
                 "bodysim_test_dense.scenario.yaml:903:5: error: the commands change the inputs at 901 distinct "
                 "times by t = 0.0901 s, and each restarts the integrator: more steps than --max-steps-per-second "
                 "900 allows by then [dynamics-scenario]"));
  r = bodysim(run + " --max-steps-per-second 1200");
  CHECK(r.status == 2);
  CHECK(contains(r.all, "bodysim_test_dense.scenario.yaml:1002:5: fatal error: the integrator needed more than 1200"));
  CHECK(contains(r.all, "1000 of them were restarts for changed commands"));
  CHECK(!contains(r.all, "stiffest part"));
  CHECK(!std::filesystem::exists(csv));
  r = bodysim(run);  // the default budget, 50,000 steps per second, runs them
  CHECK(r.status == 0);
  CHECK(contains(r.all, "0.5 s of ScoutTank simulated"));
  // 100,000 commands (--max-commands) at one time restart the integrator once: they run.
  {
    std::ofstream out(dense);
    out << "duration: 0.01\ncommands:\n";
    for (int i = 0; i < 100000; ++i) out << "  - {time: 0.005, joints: {TOWER: {target: " << i * 1e-6 << ", p: 10}}}\n";
  }
  r = bodysim(run);
  CHECK(r.status == 0);
  CHECK(contains(r.all, "0.01 s of ScoutTank simulated"));
  std::filesystem::remove(dense);
  std::filesystem::remove(csv);
}

TEST_CASE("bodysim: a simulation that crawls stops at its step budget, located at the stiff contact (exit 2)") {
  const std::string model = std::string(BODYFMT_TEST_DATA_DIR) + "/hostile/cylinder_radius_30.body";
  const Run r = bodysim("check '" + model + "'");
  CHECK(r.status == 2);
  CHECK(contains(r.all,
                 "cylinder_radius_30.body:16:9: fatal error: the integrator needed more than 50000 steps per "
                 "simulated second"));
  CHECK(contains(r.all,
                 "the floor contact of link \"BODY\" is the stiffest part: 40 contact points up to 30 m from "
                 "its centre of mass"));
  CHECK(contains(r.all, "[dynamics-work-budget]"));
  // The budget is an option; a small one stops the tank suite's first simulation too.
  const Run tank = bodysim("check --max-steps-per-second 10 '" + kScoutTank + "'");
  CHECK(tank.status == 2);
  CHECK(contains(tank.all, "the integrator needed more than 10 steps per simulated second"));
}

#ifdef BODYFMT_HAVE_MUJOCO_CROSS_CHECK
TEST_CASE("bodysim: --cross-check mujoco runs body2mjcf's export in MuJoCo 2.2.2 and agrees within T8") {
  const Run r = bodysim("check-tank --balance-inertia --cross-check mujoco '" + kScoutTank + "'");
  INFO(r.all);
  CHECK(r.status == 0);
  CHECK(contains(r.out, "PASS  MuJoCo: drive dq = +1 on both tracks: heading drift"));
  CHECK(contains(r.out, "PASS  MuJoCo vs Simbody: drive dq = +1 on both tracks: speed"));
  CHECK(contains(
      r.out, "PASS  MuJoCo vs Simbody: spin dq_L = +0.5, dq_R = -0.5: yaw rate / (2 × belt speed / track spacing)"));
  CHECK(contains(r.out, "MuJoCo vs Simbody: turret: pitch step"));
  CHECK(contains(r.out, "45 of 45 checks passed"));
}
#endif

namespace {

/// Columns of a line as a terminal shows it: UTF-8 code points (°, ², × count one each).
std::size_t columns(const std::string& line) {
  std::size_t n = 0;
  for (unsigned char c : line) n += (c & 0xC0) != 0x80 ? 1 : 0;
  return n;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST_CASE("bodysim check: every line of the report fits 100 columns and names its check in words") {
  std::vector<std::string> models = {std::string(BODYFMT_EXAMPLES_DIR) + "/arm.body",
                                     std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/locked_displaced.body"};
  const std::string gr001 = std::string(BODYFMT_SHARED_DIR) + "/corpus/choreonoid/GR001/GR001.body";
  if (std::filesystem::exists(gr001)) models.push_back(gr001);
  for (const std::string& model : models) {
    CAPTURE(model);
    const Run r = bodysim("check '" + model + "'");
    CHECK(r.status == 0);
    REQUIRE(contains(r.out, "checks passed"));
    for (const std::string& line : lines_of(r.out)) {
      CAPTURE(line);
      CHECK(columns(line) <= 100);
      // The spec's code goes last, in brackets; no symbol the user has not been told about.
      CHECK(!std::regex_search(line, std::regex("^(PASS|FAIL|SKIP)  G[0-9]")));
      for (const char* symbol : {"ω", "τ", "|Δ", "|a - g|", "I·"}) CHECK(!contains(line, symbol));
      // A yes/no check reads as words, never as "measured 1 expected 1 tolerance = 1".
      CHECK(!std::regex_search(line, std::regex(R"(measured\s+1\s+expected\s+1\s+tolerance = 1)")));
    }
  }
}

TEST_CASE("bodysim: a run that simulates nothing ends with why, the first error and the option that lets it run") {
  // SimpleTank's chassis inertia is refused; -q is not given, so its legacy keys' findings come
  // before: the end of the output must still say what stopped the run.
  const Run r = bodysim("check-tank '" + kSimpleTank + "'");
  CHECK(r.status == 2);
  const std::vector<std::string> lines = lines_of(r.all);
  std::size_t start = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind("bodysim check-tank: error: nothing was simulated", 0) == 0) start = i;
  REQUIRE(start < lines.size());
  std::string ending;
  for (std::size_t i = start; i < lines.size(); ++i) {
    CAPTURE(lines[i]);
    CHECK(columns(lines[i]) <= 100);
    ending += lines[i] + "\n";
  }
  CHECK(contains(ending, "SimpleTank.body:12:14"));
  CHECK(contains(ending, "[inertia-triangle]"));
  CHECK(contains(ending, "--balance-inertia"));
  CHECK(!contains(ending, "see above"));
}
