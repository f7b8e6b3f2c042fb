// Units end to end (issue 47): a radian-file value that a finding calls degrees is never
// converted silently by the format upgrade, the finding offers to reinterpret it, and a degree
// file's radian-looking rotation angle is flagged as joint ranges are.
#include "support/export_helpers.h"

#include <doctest/doctest.h>

#include "support/load_helpers.h"
#include "support/run_command.h"

#include "load/load_context.h"

#include <bodyfmt/angles.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using bodyfmt::test::fresh_dir;
using bodyfmt::test::read;

namespace {

using Run = bodyfmt::test::CommandResult;

Run bodycheck_in(const fs::path& dir, const std::string& args) {
  return bodyfmt::test::run_command("'" + std::string(BODYFMT_BODYCHECK) + "' --no-config " + args, dir.string());
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

// A format 1.0 radian file whose TURRET range was typed in degrees, as the tutorial writes it.
std::string radian_tank(const std::string& range_line) {
  return "format: ChoreonoidBody\n"
         "format_version: 1.0\n"
         "angle_unit: radian\n"
         "links:\n"
         "  - name: BASE\n"
         "    joint_type: free\n"
         "  - name: TURRET\n"
         "    parent: BASE\n"
         "    joint_type: revolute\n"
         "    joint_axis: [0, 0, 1]\n" +
         range_line +
         "\n"
         "    rotation: [0, 0, 1, 0.5]\n";
}

fs::path write(const std::string& dir_name, const std::string& text) {
  const fs::path dir = fresh_dir(dir_name);
  std::ofstream(dir / "tank.body") << text;
  return dir;
}

}  // namespace

TEST_CASE("bodycheck --fix --upgrade refuses to convert a range that looks like degrees, and says why") {
  const fs::path dir = write("units_upgrade_refused", radian_tank("    joint_range: [-10, 45]"));
  const std::string before = read(dir / "tank.body");
  const Run run = bodycheck_in(dir, "--fix --upgrade tank.body");
  CHECK(run.status == 2);
  CHECK(contains(run.output,
                 "tank.body: cannot fix: cannot upgrade while 1 value looks like degrees: "
                 "tank.body:11:18: joint range [-10, 45] of link \"TURRET\" is read in radians"));
  CHECK(contains(run.output, "-10 -> -572.9577951308232, 45 -> 2578.3100780887044"));
  CHECK(read(dir / "tank.body") == before);  // nothing written
}

TEST_CASE("units-range-looks-degree: its fix-it reinterprets the range as degrees, and the upgrade then writes them") {
  const fs::path dir = write("units_reinterpret", radian_tank("    joint_range: [-10, 45]"));
  const Run json = bodycheck_in(dir, "--format json tank.body");
  // The radians that -10 and 45 degrees are, in the text that reads back as the same doubles.
  CHECK(contains(json.output,
                 "\"original\": \"-10\", \"replacement\": \"-0.17453292519943295\", \"safety\": "
                 "\"unsafe\""));
  CHECK(contains(json.output,
                 "\"original\": \"45\", \"replacement\": \"0.7853981633974483\", \"safety\": "
                 "\"unsafe\""));
  // Applied by hand (bodycheck --fix never applies an unsafe fix-it), then the upgrade goes through.
  std::string text = read(dir / "tank.body");
  text.replace(text.find("[-10, 45]"), 9, "[-0.17453292519943295, 0.7853981633974483]");
  std::ofstream(dir / "tank.body") << text;
  const Run upgrade = bodycheck_in(dir, "--fix --upgrade tank.body");
  CHECK(contains(upgrade.output, "tank.body: fixed ("));
  const std::string after = read(dir / "tank.body");
  CHECK(contains(after, "    joint_range: [-10, 45]\n"));
  CHECK(contains(after, "angle_unit: degree\n"));
}

TEST_CASE("bodycheck --fix --upgrade goes through once the finding is suppressed: the user said it is radians") {
  const fs::path dir = write("units_suppressed",
                             radian_tank("    joint_range: [-10, 45]  # bodycheck: disable=units-range-looks-degree"));
  const Run run = bodycheck_in(dir, "--fix --upgrade tank.body");
  CHECK(contains(run.output, "tank.body: fixed ("));
  CHECK(contains(read(dir / "tank.body"), "joint_range: [-572.9577951308232, 2578.3100780887044]"));
}

TEST_CASE("units-velocity-looks-degree blocks the upgrade too, and offers the rad/s") {
  const fs::path dir = write("units_velocity", radian_tank("    max_joint_velocity: 180"));
  const Run json = bodycheck_in(dir, "--format json tank.body");
  CHECK(contains(json.output, "\"original\": \"180\", \"replacement\": \"3.141592653589793\", \"safety\": \"unsafe\""));
  const Run run = bodycheck_in(dir, "--fix --upgrade tank.body");
  CHECK(run.status == 2);
  CHECK(contains(run.output, "cannot upgrade while 1 value looks like degrees"));
  CHECK(contains(run.output, "[units-velocity-looks-degree]"));
}

// Judged in each file's own unit: a degree main file that includes a radian part is the part's
// unit, which the model-wide flag (the main file's) would miss.
TEST_CASE("units-range-looks-degree is judged in the unit of the file the range is written in") {
  const auto r = bodyfmt::test::load(radian_tank("    joint_range: [-90, 90]"));
  CHECK(r.has("units-range-looks-degree"));
  const auto degrees = bodyfmt::test::load(
      "format: ChoreonoidBody\nformat_version: 1.0\nangle_unit: degree\nlinks:\n  - name: BASE\n    joint_type: "
      "free\n  - name: A\n    parent: BASE\n    joint_type: revolute\n    joint_range: [-90, 90]\n");
  CHECK_FALSE(degrees.has("units-range-looks-degree"));
}

// 1.5708 degrees is a 1.5708-degree turn: the value meant π/2, a quarter turn. Small degree tilts
// (2.35, 0.2: both in the corpus), whole degrees and radian files are left alone.
TEST_CASE("units-rotation-looks-radian: a rotation angle in a degree file that looks like radians") {
  const struct {
    const char* unit;
    const char* rotation;
    const char* meant;  // the fix-it's degrees, or nullptr for no finding
  } cases[] = {
      {"degree", "[0, 0, 1, 1.5708]", "90"},
      {"degree", "[0, 0, 1, -3.1416]", "-180"},
      {"degree", "[[1, 0, 0, 0.7854], [0, 1, 0, 30]]", "45"},
      {"degree", "[0, 0, 1, 6.2832]", "360"},
      {"degree", "[0, 0, 1, 2.35]", nullptr},
      {"degree", "[0, 0, 1, 0.2]", nullptr},
      {"degree", "[0, 0, 1, 3]", nullptr},
      {"degree", "[0, 0, 1, 90]", nullptr},
      {"degree", "[0, 0, 1, 0]", nullptr},
      {"radian", "[0, 0, 1, 1.5708]", nullptr},
  };
  for (const auto& c : cases) {
    CAPTURE(c.unit);
    CAPTURE(c.rotation);
    auto r = bodyfmt::test::load(std::string("format: ChoreonoidBody\nformat_version: 1.0\nangle_unit: ") + c.unit +
                                 "\nlinks:\n  - name: BASE\n    joint_type: free\n    rotation: " + c.rotation + "\n");
    REQUIRE(r.model);
    CHECK(r.has("units-rotation-looks-radian") == (c.meant != nullptr));
    if (!c.meant) continue;
    const bodyfmt::Diagnostic d = r.take("units-rotation-looks-radian");
    CHECK(d.severity == bodyfmt::Severity::kWarning);
    CHECK(d.location.line == 7);
    REQUIRE(d.fixes.size() == 1);
    CHECK(d.fixes[0].replacement == c.meant);
    CHECK(d.fixes[0].safety == bodyfmt::FixSafety::kUnsafe);
  }
}

// The upgrade's degrees read back as the very radians (the loader computes d * kPi / 180.0), in the
// shortest such text: pi/3 is 60, where the shortest form of the product is 59.99999999999999.
TEST_CASE("load: the format upgrade writes the shortest degrees that read back as the same radians") {
  using bodyfmt::kPi;
  using bodyfmt::detail::degrees_text;
  CHECK(degrees_text(60 * kPi / 180.0) == "60");
  CHECK(degrees_text(-10 * kPi / 180.0) == "-10");
  CHECK(degrees_text(0.5) == "28.64788975654116");
  CHECK(degrees_text(0) == "0");
  for (double r : {1.5708, 1.0, -3.0, 1e-9, 6.283185307179586})
    CHECK(std::strtod(degrees_text(r).c_str(), nullptr) * kPi / 180.0 == doctest::Approx(r).epsilon(1e-15));
}
