// The command-line front every tool shares (tools/common/front.h), tried on every tool with
// the same table of inputs: --help, --version, standard input ('-', /dev/stdin, <(...)), the
// same --disable, the source line and caret, colour, usage errors and exit codes.
#include <doctest/doctest.h>

#include "support/run_command.h"

#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Tool {
  std::string name;
  std::string binary;
  std::string extra;  // arguments every run of this tool needs (an exporter's output)
  bool exporter() const { return !extra.empty(); }
  /// The exit code for a model with errors: 1, or 2 for an exporter, which writes nothing.
  int error_exit() const { return exporter() ? 2 : 1; }
};

std::vector<Tool> tools() {
  const fs::path out = fs::temp_directory_path() / "bodyfmt_front_test";
  fs::create_directories(out);
  return {
      {"bodyinfo", BODYFMT_BODYINFO, ""},
      {"bodycheck", BODYFMT_BODYCHECK, ""},
      {"body2urdf", BODYFMT_BODY2URDF, "-o '" + (out / "front.urdf").string() + "'"},
      {"body2mjcf", BODYFMT_BODY2MJCF, "-o '" + (out / "front.xml").string() + "'"},
  };
}

using Run = bodyfmt::test::CommandResult;  // stdout and stderr

/// Runs `command` with bash (for <(...)) in tests/data/bodycheck, stdout and stderr merged.
Run run(const std::string& command) {
  return bodyfmt::test::run_command(command, std::string(BODYFMT_TEST_DATA_DIR) + "/bodycheck");
}

std::string invoke(const Tool& tool, const std::string& args) {
  return "'" + tool.binary + "' " + args + (tool.extra.empty() ? "" : " " + tool.extra);
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

// warning.body: a duplicate key on line 11, column 5, and nothing else.
const std::string kWarning =
    "warning: duplicate key \"mass\" (first at line 10); the last value wins [yaml-duplicate-key]\n"
    "    mass: 1.2\n"
    "    ^\n";

}  // namespace

TEST_CASE("front: --help exits 0 and shows the shared option groups, in every tool") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    const Run r = run("'" + tool.binary + "' --help");
    CHECK(r.status == 0);
    CHECK(contains(r.output, std::string("Usage: ") + tool.name));
    for (const char* option :
         {"--version", "--stdin-filename", "--package-path", "--no-meshes", "--max-yaml-nodes", "--max-yaml-depth",
          "--enable", "--disable", "--fail-on", "--werror", "--no-config", "--quiet", "--color"})
      CHECK(contains(r.output, option));
  }
}

TEST_CASE("front: --version prints the CMake project version, in every tool") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    const Run r = run("'" + tool.binary + "' --version");
    CHECK(r.status == 0);
    CHECK(r.output == std::string(tool.name) + " " + BODYFMT_PROJECT_VERSION + "\n");
  }
}

TEST_CASE("front: '-' reads standard input, located with --stdin-filename and a caret, in every tool") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    const Run r = run("cat warning.body | " + invoke(tool, "- --stdin-filename warning.body"));
    CHECK(r.status == 0);
    CHECK(contains(r.output, "warning.body:11:5: " + kWarning));
    const Run unnamed = run("cat warning.body | " + invoke(tool, "-"));
    CHECK(contains(unnamed.output, "<stdin>:11:5: " + kWarning));
  }
}

TEST_CASE("front: /dev/stdin and a process substitution load, with source lines, in every tool") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    const Run piped = run("cat warning.body | " + invoke(tool, "/dev/stdin"));
    CHECK(piped.status == 0);
    CHECK(contains(piped.output, "/dev/stdin:11:5: " + kWarning));
    CHECK(!contains(piped.output, "canonical"));
    const Run substituted = run(invoke(tool, "<(cat warning.body)"));
    CHECK(substituted.status == 0);
    CHECK(contains(substituted.output, ":11:5: " + kWarning));
    CHECK(!contains(substituted.output, "internal-error"));
  }
}

TEST_CASE("front: concurrent runs writing the same output all succeed, and the output is whole") {
  for (const Tool& tool : tools()) {
    if (!tool.exporter()) continue;
    CAPTURE(tool.name);
    // Eight runs at once onto one destination: each must replace it in one step (exit 0), never
    // find it missing half-way through its own replacement.
    const Run r =
        run("pids=(); for i in 1 2 3 4 5 6 7 8; do " + invoke(tool, "warning.body") +
            " >/dev/null 2>&1 & pids+=($!); done; bad=0; for p in \"${pids[@]}\"; do wait $p || bad=$((bad+1)); "
            "done; echo \"failed=$bad\"");
    CHECK(r.output == "failed=0\n");
  }
}

TEST_CASE("front: the same --disable, --fail-on and --werror work in every tool") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    const Run disabled = run(invoke(tool, "--disable yaml-duplicate-key warning.body"));
    CHECK(disabled.status == 0);
    CHECK(!contains(disabled.output, "yaml-duplicate-key"));
    CHECK(run(invoke(tool, "--fail-on warning warning.body")).status == 1);
    const Run werror = run(invoke(tool, "--werror warning.body"));
    CHECK(werror.status == tool.error_exit());
    CHECK(contains(werror.output, "warning.body:11:5: error: duplicate key"));
    const Run unknown = run(invoke(tool, "--disable yaml-duplicat-key warning.body"));
    CHECK(unknown.status == 2);
    CHECK(contains(unknown.output, "did you mean 'yaml-duplicate-key'?"));
  }
}

TEST_CASE("front: a defective model gives the located error with its caret and exit 1, in every tool") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    const Run r = run(invoke(tool, "defective.body"));
    CHECK(r.status == tool.error_exit());
    CHECK(contains(r.output,
                   "defective.body:16:17: error: illegal joint type \"hinge\" [load-joint-type]\n"
                   "    joint_type: hinge\n"
                   "                ^\n"));
  }
}

TEST_CASE("front: an exporter writes nothing for a model with errors, unless --best-effort (exit 1)") {
  for (Tool tool : tools()) {
    if (!tool.exporter()) continue;
    CAPTURE(tool.name);
    // Its own output file: other cases run at the same time and write theirs.
    const fs::path out = fs::temp_directory_path() / "bodyfmt_front_test" / (std::string("best_effort_") + tool.name);
    tool.extra = "-o '" + out.string() + "'";
    fs::remove(out);
    const Run refused = run(invoke(tool, "defective.body"));
    CHECK(refused.status == 2);
    CHECK(contains(refused.output, "was not written: the model has errors (--best-effort writes it anyway)"));
    CHECK_FALSE(fs::exists(out));
    const Run best_effort = run(invoke(tool, "--best-effort defective.body"));
    CHECK(best_effort.status == 1);
    CHECK(fs::exists(out));
  }
}

TEST_CASE("front: --color always paints like GCC, never, and NO_COLOR with auto, do not") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    const Run colored = run(invoke(tool, "--color always warning.body"));
    CHECK(contains(colored.output, "\x1b[1mwarning.body:11:5:\x1b[0m \x1b[1;35mwarning:\x1b[0m duplicate key"));
    CHECK(contains(colored.output, "\x1b[1;32m    ^\x1b[0m"));
    CHECK(!contains(run(invoke(tool, "--color never warning.body")).output, "\x1b["));
    // `script` gives the tool a terminal: auto colours it, unless NO_COLOR is set.
    CHECK(contains(run("script -qec \"" + invoke(tool, "warning.body") + "\" /dev/null").output, "\x1b[1;35m"));
    CHECK(!contains(run("NO_COLOR=1 script -qec \"" + invoke(tool, "warning.body") + "\" /dev/null").output,
                    "\x1b[1;35m"));
  }
}

TEST_CASE("front: list options before the model take one value each, in every tool") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    const Run r =
        run("'" + tool.binary + "' --package-path /tmp --disable yaml-duplicate-key warning.body " + tool.extra);
    CHECK(r.status == 0);
    CHECK(!contains(r.output, "yaml-duplicate-key"));
  }
}

TEST_CASE("front: usage errors and unreadable inputs exit 2, in every tool") {
  for (const Tool& tool : tools()) {
    CAPTURE(tool.name);
    CHECK(run(invoke(tool, "--max-yaml-depth many warning.body")).status == 2);
    // A limit of 0 or less would switch its guard off: refused, in words.
    for (const char* limit :
         {"--max-yaml-nodes -5", "--max-yaml-nodes 0", "--max-yaml-depth 0", "--max-file-size -1"}) {
      CAPTURE(limit);
      const Run r = run(invoke(tool, std::string(limit) + " warning.body"));
      CHECK(r.status == 2);
      CHECK(contains(r.output, "must be a whole number above 0, not "));
    }
    CHECK(run(invoke(tool, "--color sometimes warning.body")).status == 2);
    CHECK(run(invoke(tool, "no-such-file.body")).status == 2);
    if (std::string(tool.name) == "bodycheck") continue;  // bodycheck searches directories
    const Run directory = run(invoke(tool, "configured"));
    CHECK(directory.status == 2);
    CHECK(contains(directory.output, "\"configured\" is a directory, not a .body file [io-read]"));
  }
}

TEST_CASE("front: --allow-loss accepts the named kinds of loss, still reported, and only those") {
  const std::string tank = std::string(BODYFMT_EXAMPLES_DIR) + "/simpletank.body";
  const std::string arm = std::string(BODYFMT_EXAMPLES_DIR) + "/arm.body";
  const fs::path out = fs::temp_directory_path() / "bodyfmt_front_test";
  struct Case {
    std::string binary, model, output, all_kinds, some_kinds;
  };
  // The kinds each export loses, as the tools print them ("loss kind: ...").
  const std::vector<Case> cases = {
      {BODYFMT_BODY2URDF, tank, (out / "allow.urdf").string(), "devices,dynamics,materials,tracks", "devices,tracks"},
      {BODYFMT_BODY2GLTF, tank, (out / "allow.glb").string(), "devices,tracks", "tracks"},
      {BODYFMT_BODY2MJCF, arm, (out / "allow.xml").string(), "devices,joints", "joints"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.binary);
    const std::string base = "'" + c.binary + "' '" + c.model + "' -o '" + c.output + "' ";
    const Run lossy = run(base);
    CHECK(lossy.status == 1);
    const Run allowed = run(base + "--allow-loss " + c.all_kinds);
    CHECK(allowed.status == 0);
    // Before the model, too: the option takes one list, not the model file after it.
    CHECK(run("'" + c.binary + "' --allow-loss " + c.all_kinds + " '" + c.model + "' -o '" + c.output + "'").status ==
          0);
    CHECK(contains(allowed.output, "[export-loss]"));  // still reported
    CHECK(run(base + "--allow-loss " + c.some_kinds).status == 1);
    CHECK(run(base + "--allow-loss trakcs").status == 2);
  }
}
