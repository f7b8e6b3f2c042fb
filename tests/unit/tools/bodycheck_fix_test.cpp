// bodycheck --fix on copies of tests/data/fix: what is written, what is refused, exit codes.
#include "support/export_helpers.h"

#include <doctest/doctest.h>

#include "support/run_command.h"

#include <sys/stat.h>

#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using bodyfmt::test::fresh_dir;
using bodyfmt::test::read;

namespace {

using Run = bodyfmt::test::CommandResult;  // stdout, then stderr

Run bodycheck_in(const fs::path& dir, const std::string& args) {
  return bodyfmt::test::run_command("'" + std::string(BODYFMT_BODYCHECK) + "' --no-config " + args, dir.string());
}

fs::path copy_data(const std::string& name) {
  const fs::path dir = fresh_dir("fix_" + name);
  fs::copy(fs::path(BODYFMT_TEST_DATA_DIR) / "fix", dir, fs::copy_options::recursive);
  return dir;
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

}  // namespace

TEST_CASE("bodycheck --fix: renames legacy keys in place, once in anchored text, and a second run changes nothing") {
  const fs::path dir = copy_data("legacy");
  const std::string before = read(dir / "legacy.body");
  Run run = bodycheck_in(dir, "--fix legacy.body");
  CHECK(contains(run.output, "legacy.body: fixed (13 edits)"));
  const std::string after = read(dir / "legacy.body");
  CHECK(contains(after, "COMMON: &COMMON { center_of_mass: [ 0, 0, 0.01 ], mass: 0.5 }   # one anchor, used twice\n"));
  CHECK(contains(after, "format_version: 1.0   # kept comment\n"));  // --upgrade not given
  CHECK(contains(after, "    'center_of_mass': [ 0, 0, 0 ]\n"));     // quoting kept
  CHECK(contains(after, "    \"joint_axis\": X\n"));
  CHECK(contains(after, "    joint_type: prismatic\n"));  // legacy value `slide`
  // Byte for byte: the original with each legacy spelling replaced, and nothing else.
  std::string expected = before;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"formatVersion", "format_version"},
                                 {"angleUnit", "angle_unit"},
                                 {"centerOfMass", "center_of_mass"},
                                 {"jointType: slide", "joint_type: prismatic"},
                                 {"jointType", "joint_type"},
                                 {"jointAxis", "joint_axis"},
                                 {"jointRange", "joint_range"},
                                 {"diffuseColor", "diffuse"}})
    for (std::size_t at; (at = expected.find(from)) != std::string::npos;) expected.replace(at, from.size(), to);
  CHECK(after == expected);
  Run again = bodycheck_in(dir, "--fix legacy.body");
  CHECK_FALSE(contains(again.output, "fixed ("));
  CHECK(read(dir / "legacy.body") == after);
  CHECK_FALSE(contains(again.output, "[load-legacy-key]"));
}

TEST_CASE("bodycheck --fix --dry-run prints a diff, writes nothing, and exits 1 only when there is a change") {
  const fs::path dir = copy_data("dry");
  const std::string before = read(dir / "legacy.body");
  Run run = bodycheck_in(dir, "--fix --dry-run legacy.body");
  CHECK(run.status == 1);
  CHECK(contains(run.output, "--- a/legacy.body\n+++ b/legacy.body\n@@ -1,32 +1,32 @@\n"));
  CHECK(contains(run.output,
                 "-    jointType: slide\n-    \"jointAxis\": X\n-    jointRange: [ -0.2, 0.2 ]\n"
                 "+    joint_type: prismatic\n+    \"joint_axis\": X\n+    joint_range: [ -0.2, 0.2 ]\n"));
  CHECK(read(dir / "legacy.body") == before);
  bodycheck_in(dir, "--fix legacy.body");
  Run clean = bodycheck_in(dir, "--fix --dry-run legacy.body");
  CHECK(clean.status == 0);
  CHECK_FALSE(contains(clean.output, "--- a/"));
}

TEST_CASE("bodycheck --fix refuses a read-only file and a file with YAML errors: nothing written, exit 2") {
  const fs::path dir = copy_data("refuse");
  const std::string before = read(dir / "legacy.body");
  fs::permissions(dir / "legacy.body", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  Run read_only = bodycheck_in(dir, "--fix legacy.body");
  CHECK(read_only.status == 2);
  CHECK(contains(read_only.output, "legacy.body: cannot fix: legacy.body: the file is read-only (mode 0444)"));
  CHECK(read(dir / "legacy.body") == before);
  for (const auto& entry : fs::directory_iterator(dir))  // no temporary file left behind
    CHECK(entry.path().filename().string().find(".bodycheck-") == std::string::npos);

  const std::string broken = read(dir / "yaml_error.body");
  Run yaml = bodycheck_in(dir, "--fix yaml_error.body");
  CHECK(yaml.status == 2);
  CHECK(contains(yaml.output, "[yaml-syntax]"));
  CHECK(contains(yaml.output, "yaml_error.body: cannot fix: the file does not load"));
  CHECK(read(dir / "yaml_error.body") == broken);
  CHECK(bodycheck_in(dir, "--fix - < legacy.body").status == 2);  // standard input cannot be fixed in place
}

TEST_CASE("bodycheck --fix edits a SubBody file only when it is named or with --fix-includes") {
  const fs::path dir = copy_data("includes") / "include";
  const std::string part = read(dir / "part.body");
  Run main_only = bodycheck_in(dir, "--fix main.body");
  CHECK(read(dir / "part.body") == part);
  CHECK(contains(main_only.output, "part.body:5:5: warning: legacy key \"jointType\""));
  bodycheck_in(dir, "--fix main.body part.body");
  CHECK(contains(read(dir / "part.body"), "    joint_type: revolute\n"));
  const fs::path dir2 = copy_data("includes2") / "include";
  bodycheck_in(dir2, "--fix --fix-includes main.body");
  CHECK(contains(read(dir2 / "part.body"), "    joint_type: revolute\n"));
}

TEST_CASE("bodycheck --fix keeps the file's permissions, --upgrade rewrites the header of a degree file") {
  const fs::path dir = copy_data("perms");
  fs::permissions(dir / "legacy.body", fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  bodycheck_in(dir, "--fix --upgrade legacy.body");
  CHECK(fs::status(dir / "legacy.body").permissions() ==
        (fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read));
  const std::string after = read(dir / "legacy.body");
  CHECK(contains(after, "format_version: 2.0   # kept comment\nangle_unit: degree\n"));
}

TEST_CASE("bodycheck --format json carries the fix-its with byte offsets and their safety") {
  const fs::path dir = copy_data("json");
  Run run = bodycheck_in(dir, "--format json legacy.body");
  CHECK(contains(run.output,
                 "\"fixes\": [{\"file\": \"legacy.body\", \"line\": 4, \"column\": 1, \"offset\": 196, "
                 "\"length\": 13, \"original\": \"formatVersion\", \"replacement\": \"format_version\", "
                 "\"safety\": \"safe\"}]"));
  CHECK(contains(run.output, "\"original\": \"1.0\", \"replacement\": \"2.0\", \"safety\": \"upgrade\""));
}

TEST_CASE("bodycheck --fix: an edit that would change another use of shared text is left out with a note") {
  const fs::path dir = copy_data("shared");
  // The upgrade would write the revolute's range in degrees into the anchor the prismatic joint
  // merges too: the file stays format 1.0 in radians, its legacy keys are renamed.
  const std::string range_before = read(dir / "shared_range_v1.body");
  Run run = bodycheck_in(dir, "--fix --upgrade shared_range_v1.body");
  INFO(run.output);
  CHECK(run.status == 0);  // what is left are notes: the upgrade not made, the info key
  CHECK(contains(run.output,
                 "shared_range_v1.body:6:16: note: the format upgrade is left as it is: the edited text is shared "
                 "with another use (an anchor, alias or merge), which the edit would change too (link "
                 "\"B\" joint_range: [-1, 1] != [-57.29577951308232, 57.29577951308232]) [fix-left-out]"));
  CHECK(contains(run.output, "shared_range_v1.body: fixed ("));
  CHECK(!contains(run.output, "a bug in a fix-it"));
  const std::string range_after = read(dir / "shared_range_v1.body");
  CHECK(contains(range_after, "format_version: 1.0\nangle_unit: radian\n"));
  CHECK(contains(range_after, "RANGE: &R { joint_range: [ -1, 1 ], joint_axis: Z }\n"));
  CHECK(!contains(range_after, "jointType"));
  std::string expected = range_before;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"formatVersion", "format_version"},
                                 {"angleUnit", "angle_unit"},
                                 {"centerOfMass", "center_of_mass"},
                                 {"jointType", "joint_type"},
                                 {"jointAxis", "joint_axis"},
                                 {"jointRange", "joint_range"},
                                 {"jointId", "joint_id"}})
    for (std::size_t at; (at = expected.find(from, 300)) != std::string::npos;) expected.replace(at, from.size(), to);
  CHECK(range_after == expected);
  // A second run finds only the upgrade it cannot make, and changes nothing.
  Run again = bodycheck_in(dir, "--fix --upgrade shared_range_v1.body");
  CHECK(!contains(again.output, "fixed ("));
  CHECK(read(dir / "shared_range_v1.body") == range_after);

  // A legacy joint type whose text is also another link's parent: that value stays.
  const std::string type_before = read(dir / "aliased_joint_type.body");
  run = bodycheck_in(dir, "--fix aliased_joint_type.body");
  INFO(run.output);
  CHECK(contains(run.output,
                 "aliased_joint_type.body:17:19: note: this fix-it is left as it is: the edited text is shared with "
                 "another use (an anchor, alias or merge), which the edit would change too"));
  CHECK(contains(run.output, "aliased_joint_type.body: fixed ("));
  const std::string type_after = read(dir / "aliased_joint_type.body");
  CHECK(contains(type_after, "    joint_type: &t slide\n"));
  CHECK(contains(type_after, "    parent: *t\n"));
  expected = type_before;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"formatVersion", "format_version"},
                                 {"angleUnit", "angle_unit"},
                                 {"centerOfMass", "center_of_mass"},
                                 {"jointType", "joint_type"},
                                 {"jointAxis", "joint_axis"},
                                 {"jointId", "joint_id"}})
    for (std::size_t at; (at = expected.find(from, 250)) != std::string::npos;) expected.replace(at, from.size(), to);
  CHECK(type_after == expected);
  again = bodycheck_in(dir, "--fix aliased_joint_type.body");
  CHECK(!contains(again.output, "fixed ("));
  CHECK(read(dir / "aliased_joint_type.body") == type_after);
}

// --fix=geometry --all-links: every link's mass data from its shapes, RigidBody elements included, where
// --fix=geometry changes only the CHASSIS (the one link a rule flags). TURRET_Y's RigidBody, 4 kg
// around a box 0.2 x 0.2 x 0.1, gets 4 (0.2² + 0.1²) / 12 = 0.0166666667 about X (written 0.1,
// six times too much) and its centre at the box's (written z = 0.025); a track (1 kg) its
// trapezoid's centroid h (2a + b) / (3 (a + b)) - 0.1 = -0.0142857143. The fixed model passes
// the proof (only what was recomputed changed) and then has no inertia finding.
TEST_CASE("bodycheck --fix=geometry --all-links recomputes every link, RigidBody elements included") {
  const fs::path dir = fresh_dir("fix_geometry_all");
  fs::copy_file(fs::path(BODYFMT_EXAMPLES_DIR) / "simpletank.body", dir / "tank.body");
  fs::permissions(dir / "tank.body", fs::perms::owner_write, fs::perm_options::add);
  const Run flagged = bodycheck_in(dir, "--fix=geometry --dry-run tank.body");
  CHECK(flagged.status == 1);
  CHECK(contains(flagged.output, "+    inertia: [ 0.0666666667, 0,   0,\n"));
  CHECK_FALSE(contains(flagged.output, "0.0166666667"));

  const Run all = bodycheck_in(dir, "--fix=geometry --all-links tank.body");
  CHECK(contains(all.output, "tank.body: fixed (21 edits)"));
  const std::string after = read(dir / "tank.body");
  CHECK(contains(after,
                 "        center_of_mass: [0, 0, 0]\n"
                 "        inertia: [ 0.0166666667, 0,   0,\n"
                 "                   0,   0.0166666667, 0,\n"
                 "                   0,   0,   0.0266666667 ]\n"));
  CHECK(contains(after, "    center_of_mass: [0, 0, -0.0142857143]\n    mass: 1.0\n"));
  const Run check = bodycheck_in(dir, "tank.body");
  CHECK(check.status == 0);
  CHECK_FALSE(contains(check.output, "[inertia-"));
  const Run again = bodycheck_in(dir, "--fix=geometry --all-links --dry-run tank.body");
  CHECK(again.status == 0);
}

// The tutorial's CHASSIS inertia: one sentence that says what is wrong, a hint that names the
// fix; the engines and their tolerances are the rule's documentation.
TEST_CASE("bodycheck: the triangle inequality in one sentence, with --fix=geometry as the hint") {
  const Run run = bodycheck_in(BODYFMT_EXAMPLES_DIR, "simpletank.body");
  CHECK(contains(run.output,
                 "error: inertia of link \"CHASSIS\" is impossible for a rigid body: principal moments "
                 "(0.1, 0.1, 0.5) break the triangle inequality (0.1 + 0.1 < 0.5) [inertia-triangle]\n"));
  CHECK(contains(run.output, "note: compute it from the link's shapes with bodycheck --fix=geometry"));
  CHECK_FALSE(contains(run.output, "Drake"));
  const Run explain = bodycheck_in(".", "--explain inertia-triangle");
  CHECK(contains(explain.output, "Drake one beyond 16*eps*max(1, tr/2)"));
  CHECK(contains(explain.output, "gz-math one beyond 10*eps*tr/2"));
}
