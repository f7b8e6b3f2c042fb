// Loader unit tests for load/load_context.cpp: where diagnostics point, including values
// reached through YAML aliases, and YAML-layer diagnostics passing through the loader.

#include "support/load_helpers.h"

using namespace bodyfmt;
using bodyfmt::test::load;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

TEST_CASE("load: a diagnostic on an aliased scalar is at the anchored text, via the alias") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
AXES:
  bad: &BAD W
links:
  - name: A
  - name: B
    parent: A
    joint_type: revolute
    joint_axis: *BAD
)");
  auto d = r.take("load-axis");
  CHECK(pos(d) == Pos{4, 8});  // the anchored text
  REQUIRE(d.via.has_value());
  CHECK(pos(*d.via) == Pos{10, 17});  // the alias use site
  CHECK(d.via->file == "test.body");
  r.expect_clean();
}

TEST_CASE("load: a diagnostic on an aliased mapping is at the anchored text, via the alias") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
DEVICES:
  cam: &CAM
    type: Camera
    name: cam
links:
  - name: A
    elements:
      - *CAM
)");
  auto d = r.take("device-camera-dropped");
  CHECK(pos(d) == Pos{4, 8});
  REQUIRE(d.via.has_value());
  CHECK(pos(*d.via) == Pos{10, 9});
  r.expect_clean();
}

TEST_CASE("load: a diagnostic without an alias has no via") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
links:
  - name: A
    joint_axis: W
)");
  auto d = r.take("load-axis");
  CHECK(pos(d) == Pos{5, 17});
  CHECK(d.location.file == "test.body");
  CHECK_FALSE(d.via.has_value());
  r.expect_clean();
}

TEST_CASE("load: yaml-duplicate-key passes through with its location, the last value wins") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
links:
  - name: A
    mass: 1
    mass: 2
)");
  auto d = r.take("yaml-duplicate-key");
  CHECK(d.severity == Severity::kWarning);
  CHECK(pos(d) == Pos{6, 5});
  const auto& c = r.link("A").mass_contributions;
  REQUIRE(c.size() == 1);
  CHECK(c[0].mass == 2);
  r.expect_clean();
}

TEST_CASE("load: diagnostics carry the file name given to load_body_string") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
links:
  - name: A
    joint_axis: W
)",
                "dir/robot.body");
  auto d = r.take("load-axis");
  CHECK(d.location.file == "dir/robot.body");
  CHECK(r.m().name == "robot");
  r.expect_clean();
}
