// One defective file per rule under tests/data/validate/<rule-id>.body: each test loads it,
// derives and checks, and asserts the rule id and its exact line and column. The loader's own
// rules that issue 4 lists have a file here too, so that every rule of the issue has one.
// Any other warning or error must be listed as an allowed companion.

#include "support/load_helpers.h"
#include "unit/validate/validate_support.h"

#include <doctest/doctest.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <algorithm>
#include <initializer_list>
#include <string>

using bodyfmt::Diagnostic;
using bodyfmt::Severity;
using bodyfmt::test::Pos;

namespace {

std::string data(const std::string& name) { return std::string(BODYFMT_TEST_DATA_DIR) + "/validate/" + name; }

// Checks `file` reports `rule_id` at `at` (in that file) and nothing else at warning level or
// above except the `allowed` rule ids.
void expect_finding(const std::string& file, const std::string& rule_id, Pos at,
                    std::initializer_list<const char*> allowed = {}) {
  const auto result = bodyfmt::test::check_file(data(file));
  INFO("diagnostics:\n" << bodyfmt::test::describe(result.diagnostics));
  auto it = std::find_if(result.diagnostics.begin(), result.diagnostics.end(),
                         [&](const Diagnostic& d) { return d.rule_id == rule_id; });
  REQUIRE(it != result.diagnostics.end());
  CHECK(bodyfmt::test::pos(*it) == at);
  CHECK(it->location.file.str().find(file) != std::string::npos);
  CHECK(!it->message.empty());
  for (const Diagnostic& d : result.diagnostics) {
    if (d.severity == Severity::kNote || d.rule_id == rule_id) continue;
    const bool ok = std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return d.rule_id == a; });
    CHECK_MESSAGE(ok, "unexpected companion finding [" << d.rule_id << "]");
  }
}

const Diagnostic* find(const std::vector<Diagnostic>& diagnostics, const std::string& rule_id) {
  auto it =
      std::find_if(diagnostics.begin(), diagnostics.end(), [&](const Diagnostic& d) { return d.rule_id == rule_id; });
  return it == diagnostics.end() ? nullptr : &*it;
}

}  // namespace

TEST_CASE("validate: a clean model gives no findings") {
  const auto result = bodyfmt::test::check_file(data("clean.body"));
  INFO("diagnostics:\n" << bodyfmt::test::describe(result.diagnostics));
  CHECK(result.loaded);
  CHECK(result.diagnostics.empty());
}

// ---- Inertia

TEST_CASE("validate: inertia-asymmetric") { expect_finding("inertia-asymmetric.body", "inertia-asymmetric", {10, 14}); }

TEST_CASE("validate: inertia-not-positive-definite") {
  expect_finding("inertia-not-positive-definite.body", "inertia-not-positive-definite", {10, 14});
  const auto result = bodyfmt::test::check_file(data("inertia-not-positive-definite.body"));
  const Diagnostic* d = find(result.diagnostics, "inertia-not-positive-definite");
  REQUIRE(d);
  // The negative moment is clamped to 0, then raised to the margin s = 1e-7 * (0.015 + 0.015)
  // that keeps A + B >= C through rounding: diag(0.015, 0.015, 3e-9).
  CHECK(d->fix_hint.find("[0.015, 0, 0, 0.015, 0, 3e-09]") != std::string::npos);
}

TEST_CASE("validate: inertia-triangle") {
  // The tutorial's SimpleTank chassis, diag(0.1, 0.1, 0.5).
  expect_finding("inertia-triangle.body", "inertia-triangle", {10, 14});
  const auto result = bodyfmt::test::check_file(data("inertia-triangle.body"));
  const Diagnostic* d = find(result.diagnostics, "inertia-triangle");
  REQUIRE(d);
  CHECK(d->severity == Severity::kError);
  // One sentence: what is wrong; which engines refuse it at which tolerance is --explain's.
  CHECK(d->message.find("(0.1 + 0.1 < 0.5)") != std::string::npos);
  CHECK(d->message.find("Drake") == std::string::npos);
  // The fix first (the link has a shape), then the projection onto A + B = C: each moment moves
  // by 0.3 / 3.
  CHECK(d->fix_hint.find("compute it from the link's shapes with bodycheck --fix=geometry") == 0);
  CHECK(d->fix_hint.find("[0.2, 0, 0, 0.2, 0, 0.4]") != std::string::npos);
}

TEST_CASE("validate: inertia-triangle names only MuJoCo for a violation within Drake's tolerance") {
  const auto r = bodyfmt::test::load_v2(R"(
links:
  - name: BASE
    joint_type: free
    mass: 1
    inertia: [1, 0, 0, 1, 0, 2.000000000000001]
)");
  bodyfmt::CollectingSink sink;
  const auto derived = bodyfmt::compute_derived(r.m(), sink);
  bodyfmt::validate::check_model(r.m(), derived, {}, sink);
  const Diagnostic* d = find(sink.diagnostics(), "inertia-triangle");
  REQUIRE(d);
  // 6 digits would show "1 + 1 < 2": the margin instead, and who still takes the tensor.
  CHECK(d->message.find("(A + B - C = -8.88178e-16); within Drake's and gz-math's rounding tolerances, so "
                        "MuJoCo refuses it") != std::string::npos);
  // No shape to compute it from: the nearest valid tensor is the hint.
  CHECK(d->fix_hint.find("--fix=geometry") == std::string::npos);
}

TEST_CASE("validate: inertia-nonpositive-mass") {
  expect_finding("inertia-nonpositive-mass.body", "inertia-nonpositive-mass", {19, 11});
}

TEST_CASE("validate: inertia-tiny") { expect_finding("inertia-tiny.body", "inertia-tiny", {20, 14}); }

TEST_CASE("validate: inertia-com-outside") {
  expect_finding("inertia-com-outside.body", "inertia-com-outside", {10, 21});
}

TEST_CASE("validate: inertia-implausible") {
  expect_finding("inertia-implausible.body", "inertia-implausible", {10, 14});
  const auto result = bodyfmt::test::check_file(data("inertia-implausible.body"));
  const Diagnostic* d = find(result.diagnostics, "inertia-implausible");
  REQUIRE(d);
  CHECK(d->message.find("66.6667 times") != std::string::npos);  // 3 / (1/6 * 0.27)
}

TEST_CASE("validate: an inertia the loader refused is not judged (load-inertia-size alone)") {
  // A 5-element link inertia and a 7-element RigidBody inertia: each is load-inertia-size at
  // its value; the zero tensor left in their place is no inertia-tiny or inertia-implausible.
  const auto result = bodyfmt::test::check_file(data("load-inertia-size.body"));
  INFO("diagnostics:\n" << bodyfmt::test::describe(result.diagnostics));
  int size = 0;
  for (const Diagnostic& d : result.diagnostics) {
    size += d.rule_id == "load-inertia-size" ? 1 : 0;
    CHECK_MESSAGE(d.rule_id.rfind("inertia-", 0) != 0, "judged a refused inertia [" << d.rule_id << "]");
  }
  CHECK(size == 2);
}

// ---- Joints

TEST_CASE("validate: joint-id-duplicate") { expect_finding("joint-id-duplicate.body", "joint-id-duplicate", {30, 15}); }
TEST_CASE("validate: the links of a ContinuousTrack share its joint_id without joint-id-duplicate") {
  // Choreonoid's clones keep the template's joint id (the loader warns, load-track-shared-joint);
  // another link with that id is still a duplicate.
  expect_finding("track-shared-joint-id.body", "joint-id-duplicate", {21, 15}, {"load-track-shared-joint"});
  const auto result = bodyfmt::test::check_file(data("track-shared-joint-id.body"));
  CHECK(std::count_if(result.diagnostics.begin(), result.diagnostics.end(),
                      [](const Diagnostic& d) { return d.rule_id == "joint-id-duplicate"; }) == 1);
}

TEST_CASE("validate: joint-id-gap") {
  expect_finding("joint-id-gap.body", "joint-id-gap", {30, 15});
  const auto result = bodyfmt::test::check_file(data("joint-id-gap.body"));
  const Diagnostic* d = find(result.diagnostics, "joint-id-gap");
  REQUIRE(d);
  CHECK(d->message.find("1, 2 are missing") != std::string::npos);
}

TEST_CASE("validate: joint-id-on-fixed") { expect_finding("joint-id-on-fixed.body", "joint-id-on-fixed", {18, 15}); }
TEST_CASE("validate: joint-axis-zero") { expect_finding("joint-axis-zero.body", "joint-axis-zero", {18, 17}); }
TEST_CASE("validate: joint-axis-not-unit") {
  expect_finding("joint-axis-not-unit.body", "joint-axis-not-unit", {18, 17});
}
TEST_CASE("validate: joint-range-reversed") {
  expect_finding("joint-range-reversed.body", "joint-range-reversed", {20, 18});
}
TEST_CASE("validate: joint-range-zero-width") {
  expect_finding("joint-range-zero-width.body", "joint-range-zero-width", {20, 18});
}
TEST_CASE("validate: joint-velocity-negative") {
  expect_finding("joint-velocity-negative.body", "joint-velocity-negative", {20, 25});
}
TEST_CASE("validate: load-joint-type (loader)") { expect_finding("load-joint-type.body", "load-joint-type", {11, 17}); }

// ---- Units

TEST_CASE("validate: units-range-looks-radian") {
  expect_finding("units-range-looks-radian.body", "units-range-looks-radian", {20, 18});
  const auto result = bodyfmt::test::check_file(data("units-range-looks-radian.body"));
  const Diagnostic* d = find(result.diagnostics, "units-range-looks-radian");
  REQUIRE(d);
  CHECK(d->fix_hint.find("[-90, 90]") != std::string::npos);
}

TEST_CASE("validate: units-range-looks-radian leaves small whole-degree ranges alone") {
  const auto r = bodyfmt::test::load_v2(R"(
links:
  - name: BASE
    joint_type: free
  - name: A
    parent: BASE
    joint_type: revolute
    joint_range: [-3, 5]
  - name: B
    parent: BASE
    joint_type: revolute
    joint_range: [-10, 45]
)");
  bodyfmt::CollectingSink sink;
  const auto derived = bodyfmt::compute_derived(r.m(), sink);
  bodyfmt::validate::check_model(r.m(), derived, {}, sink);
  CHECK_FALSE(sink.has("units-range-looks-radian"));
}

TEST_CASE("validate: units-range-looks-degree (a degree range in a radian file)") {
  expect_finding("units-range-looks-degree.body", "units-range-looks-degree", {20, 18});
  const auto result = bodyfmt::test::check_file(data("units-range-looks-degree.body"));
  const Diagnostic* d = find(result.diagnostics, "units-range-looks-degree");
  REQUIRE(d);
  CHECK(d->severity == Severity::kError);
  CHECK(d->fix_hint.find("[-1.5708, 1.5708]") != std::string::npos);
}

TEST_CASE("validate: units-velocity-looks-degree (deg/s in a radian file)") {
  expect_finding("units-velocity-looks-degree.body", "units-velocity-looks-degree", {20, 25});
  const auto result = bodyfmt::test::check_file(data("units-velocity-looks-degree.body"));
  const Diagnostic* d = find(result.diagnostics, "units-velocity-looks-degree");
  REQUIRE(d);
  CHECK(d->severity == Severity::kError);
  CHECK(d->fix_hint.find("3.1416") != std::string::npos);
}

// The thresholds of the two rules, each side: a limit beyond one turn (2pi + 0.002) that is a
// multiple of 0.5 and at most 360 is a degree range; a velocity beyond 16pi rad/s, a multiple of
// 0.5 and at most 3600 is deg/s. Radian values (pi, 2pi, 4pi as decimals), unlimited joints and
// degree files are left alone.
TEST_CASE("validate: units-*-looks-degree thresholds") {
  const struct {
    const char* unit;
    const char* line;
    const char* rule;  // expected, or nullptr
  } cases[] = {
      {"radian", "joint_range: [-90, 90]", "units-range-looks-degree"},
      {"radian", "joint_range: [0, 360]", "units-range-looks-degree"},
      {"radian", "joint_range: [-7, 7]", "units-range-looks-degree"},
      {"radian", "joint_range: [-22.5, 0]", "units-range-looks-degree"},
      {"radian", "joint_range: [-6.28, 6.28]", nullptr},
      {"radian", "joint_range: [-6.285, 6.285]", nullptr},
      {"radian", "joint_range: [-12.566, 12.566]", nullptr},
      {"radian", "joint_range: [-3.14, 3.14]", nullptr},
      {"radian", "joint_range: [-361, 361]", nullptr},
      {"radian", "joint_range: [unlimited, unlimited]", nullptr},
      {"radian", "joint_range: [-90, unlimited]", "units-range-looks-degree"},
      {"degree", "joint_range: [-90, 90]", nullptr},
      {"radian", "max_joint_velocity: 180", "units-velocity-looks-degree"},
      {"radian", "max_joint_velocity: 51", "units-velocity-looks-degree"},
      {"radian", "joint_velocity_range: [-90, 90]", "units-velocity-looks-degree"},
      {"radian", "max_joint_velocity: 50", nullptr},
      {"radian", "max_joint_velocity: 6.28", nullptr},
      {"radian", "max_joint_velocity: 60.3", nullptr},
      {"radian", "max_joint_velocity: 3601", nullptr},
      {"degree", "max_joint_velocity: 180", nullptr},
  };
  for (const auto& c : cases) {
    CAPTURE(c.unit);
    CAPTURE(c.line);
    const auto r =
        bodyfmt::test::load(std::string("format: ChoreonoidBody\nformat_version: 1.0\nangle_unit: ") + c.unit +
                            "\nlinks:\n  - name: BASE\n    joint_type: free\n  - name: A\n    parent: "
                            "BASE\n    joint_type: revolute\n    " +
                            c.line + "\n");
    // The loader reports them (it sees each file's unit and the text its fix-it edits).
    CHECK(r.has("units-range-looks-degree") == (c.rule && std::string(c.rule) == "units-range-looks-degree"));
    CHECK(r.has("units-velocity-looks-degree") == (c.rule && std::string(c.rule) == "units-velocity-looks-degree"));
  }
}

TEST_CASE("validate: units-prismatic-millimetres") {
  expect_finding("units-prismatic-millimetres.body", "units-prismatic-millimetres", {20, 18});
}
TEST_CASE("validate: units-mesh-millimetres") {
  // The 300 m mesh also makes the link's inertia look implausible for its bounds.
  expect_finding("units-mesh-millimetres.body", "units-mesh-millimetres", {14, 9}, {"inertia-implausible"});
}
TEST_CASE("validate: units-radian-in-2.0 (loader)") {
  expect_finding("units-radian-in-2.0.body", "units-radian-in-2.0", {3, 13});
}

// ---- Structure

TEST_CASE("validate: structure-duplicate-device") {
  // At the second device's name: value (issue 15), not at its node.
  expect_finding("structure-duplicate-device.body", "structure-duplicate-device", {18, 15});
}
TEST_CASE("validate: structure-duplicate-link (loader)") {
  expect_finding("structure-duplicate-link.body", "structure-duplicate-link", {9, 11});
}
TEST_CASE("validate: structure-unknown-parent (loader)") {
  expect_finding("structure-unknown-parent.body", "structure-unknown-parent", {10, 13});
}
TEST_CASE("validate: structure-cycle (loader)") {
  expect_finding("structure-cycle.body", "structure-cycle", {12, 13}, {"structure-unreachable"});
}
TEST_CASE("validate: structure-unreachable (loader)") {
  // Only a cycle can cut links off from the root (every parent must name a link).
  expect_finding("structure-unreachable.body", "structure-unreachable", {9, 5}, {"structure-cycle"});
}
TEST_CASE("validate: structure-root-link (loader)") {
  expect_finding("structure-root-link.body", "structure-root-link", {4, 12});
}
TEST_CASE("validate: load-unknown-key with a did-you-mean hint (loader)") {
  expect_finding("load-unknown-key.body", "load-unknown-key", {13, 5});
  const auto result = bodyfmt::test::check_file(data("load-unknown-key.body"));
  CHECK(find(result.diagnostics, "load-unknown-key")->message.find("joint_name") != std::string::npos);
}
TEST_CASE("validate: load-unknown-model-key, an error with a did-you-mean (loader)") {
  expect_finding("load-unknown-model-key.body", "load-unknown-model-key", {13, 5});
  const auto result = bodyfmt::test::check_file(data("load-unknown-model-key.body"));
  const Diagnostic* d = find(result.diagnostics, "load-unknown-model-key");
  CHECK(d->severity == Severity::kError);
  CHECK(d->message.find("did you mean \"joint_range\"?") != std::string::npos);
}
TEST_CASE("validate: load-legacy-key (loader)") { expect_finding("load-legacy-key.body", "load-legacy-key", {11, 5}); }
TEST_CASE("validate: yaml-duplicate-key (loader)") {
  expect_finding("yaml-duplicate-key.body", "yaml-duplicate-key", {9, 5});
}
TEST_CASE("validate: load-unknown-node-type (loader)") {
  expect_finding("load-unknown-node-type.body", "load-unknown-node-type", {10, 15});
}
TEST_CASE("validate: load-plugin-node (loader)") {
  expect_finding("load-plugin-node.body", "load-plugin-node", {10, 9});
}
TEST_CASE("validate: yaml-undefined-alias (loader)") {
  expect_finding("yaml-undefined-alias.body", "yaml-undefined-alias", {9, 21});
}
TEST_CASE("validate: appearance-value-range (loader), and MuJoCo reads the clamped export") {
  expect_finding("appearance-value-range.body", "appearance-value-range", {13, 44});
  // Found by fuzz_mjcf: a diffuse of 4e68 was written as rgba="4e+68 ..." and MuJoCo refused the
  // whole file ("problem reading attribute 'rgba'"). The exports now write 1 and alpha 1.
  const std::string body = std::string(BODYFMT_TEST_DATA_DIR) + "/validate/appearance-value-range.body";
  const std::string xml = (std::filesystem::temp_directory_path() / "bodyfmt_colour_range.xml").string();
  REQUIRE(std::system(
              ("'" + std::string(BODYFMT_BODY2MJCF) + "' -q '" + body + "' -o '" + xml + "' 2>/dev/null").c_str()) ==
          0);
  std::ifstream in(xml);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("rgba=\"1 0.9 0.5 1\"") != std::string::npos);
}
TEST_CASE("validate: yaml-anchor-redefined (loader)") {
  expect_finding("yaml-anchor-redefined.body", "yaml-anchor-redefined", {5, 4});
}

// ---- Geometry

TEST_CASE("validate: geometry-zero-size") { expect_finding("geometry-zero-size.body", "geometry-zero-size", {12, 9}); }
TEST_CASE("validate: geometry-invalid-size (loader)") {
  // compute_derived reports the shape again when it tessellates it.
  expect_finding("geometry-invalid-size.body", "geometry-invalid-size", {11, 43});
}
TEST_CASE("validate: geometry-degenerate Extrusion (loader)") {
  expect_finding("geometry-degenerate-extrusion.body", "geometry-degenerate", {11, 19}, {"geometry-invalid-size"});
}
TEST_CASE("validate: geometry-degenerate ElevationGrid (loader)") {
  expect_finding("geometry-degenerate-elevation-grid.body", "geometry-degenerate", {11, 19}, {"geometry-invalid-size"});
}
TEST_CASE("validate: geometry-index-out-of-range (loader)") {
  expect_finding("geometry-index-out-of-range.body", "geometry-index-out-of-range", {11, 89});
}
TEST_CASE("validate: geometry-unknown-type (loader)") {
  expect_finding("geometry-unknown-type.body", "geometry-unknown-type", {11, 27});
}

// ---- Resources

TEST_CASE("validate: mesh-file-missing (loader)") {
  expect_finding("mesh-file-missing.body", "mesh-file-missing", {11, 42});  // the uri: value
}
TEST_CASE("validate: resource-absolute-path") {
  expect_finding("resource-absolute-path.body", "resource-absolute-path", {14, 9}, {"mesh-file-missing"});
}
TEST_CASE("validate: resource-case-mismatch") {
  // On a case-sensitive file system the loader cannot find the file either.
  expect_finding("resource-case-mismatch.body", "resource-case-mismatch", {14, 9}, {"mesh-file-missing"});
  const auto result = bodyfmt::test::check_file(data("resource-case-mismatch.body"));
  CHECK(find(result.diagnostics, "resource-case-mismatch")->message.find("small_part.obj") != std::string::npos);
}

// ---- Devices

// Device findings point at the value of the parameter that is wrong (issue 15): field_of_view,
// width, far_clip_distance (near 10 >= far 1) and intensity, not at the device's node (14:9).
TEST_CASE("validate: device-fov") { expect_finding("device-fov.body", "device-fov", {17, 24}); }
TEST_CASE("validate: device-resolution") { expect_finding("device-resolution.body", "device-resolution", {17, 16}); }
TEST_CASE("validate: device-clip") { expect_finding("device-clip.body", "device-clip", {18, 28}); }
TEST_CASE("validate: device-light") { expect_finding("device-light.body", "device-light", {16, 20}); }

namespace {
bodyfmt::CollectingSink check_text(std::string_view text) {
  auto r = bodyfmt::test::load_v2(text);
  bodyfmt::CollectingSink sink;
  const auto derived = bodyfmt::compute_derived(r.m(), sink);
  bodyfmt::validate::check_model(r.m(), derived, {}, sink);
  return sink;
}
}  // namespace

TEST_CASE("validate: device-fov accepts up to 360 degrees for a fisheye lens") {
  // TankBody's "Theta": DUAL_FISHEYE with field_of_view 180.
  auto sink = check_text(R"(
links:
  - name: BASE
    joint_type: free
    elements:
      - type: Camera
        name: THETA
        format: COLOR
        lens_type: DUAL_FISHEYE
        field_of_view: 180
)");
  CHECK_FALSE(sink.has("device-fov"));
}

TEST_CASE("validate: plausibility warnings skip links welded to the world") {
  // A fixed root (a floor, a table) never moves, so its mass data is never simulated.
  auto sink = check_text(R"(
links:
  - name: FLOOR
    joint_type: fixed
    mass: 1
    center_of_mass: [5, 0, 0]
    inertia: [1, 0, 0, 1, 0, 1]
    elements:
      - type: Shape
        geometry: { type: Box, size: [0.1, 0.1, 0.1] }
)");
  CHECK_FALSE(sink.has("inertia-implausible"));
  CHECK_FALSE(sink.has("inertia-com-outside"));
}

TEST_CASE("validate: a massless moving link passes when a fixed child carries the mass") {
  // MuJoCo's rule: a moving body may be massless if a static descendant has mass.
  auto sink = check_text(R"(
links:
  - name: BASE
    joint_type: free
    mass: 1
    inertia: [0.1, 0, 0, 0.1, 0, 0.1]
  - name: ARM
    parent: BASE
    joint_type: revolute
    mass: 0
  - name: HAND
    parent: ARM
    joint_type: fixed
    mass: 1
    inertia: [0.1, 0, 0, 0.1, 0, 0.1]
)");
  CHECK_FALSE(sink.has("inertia-nonpositive-mass"));
  CHECK_FALSE(sink.has("inertia-tiny"));
}
