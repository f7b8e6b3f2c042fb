// The fix-its of bodycheck --fix=geometry (issue 39): numbers replaced where they are written,
// keys inserted where missing, nothing offered for text the edit cannot own.

#include <bodyfmt/fix.h>
#include <bodyfmt/geometry_fix.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <string>

using namespace bodyfmt;

namespace {

const char* kHead = R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
name: Fix
root_link: BASE
links:
  - name: BASE
    joint_type: free
)";

Model load(const std::string& text) {
  CollectingSink sink;
  LoadOptions options;
  options.load_meshes = false;
  auto model = load_body_string(text, "fix.body", options, sink);
  REQUIRE(model);
  return *model;
}

MassProperties keys() {
  MassProperties k;
  k.mass = 8;
  k.center_of_mass = Eigen::Vector3d(0.1, 1e-17, 0);  // the 1e-17 is rounding: written 0
  k.inertia = Eigen::Vector3d(0.25, 1.0 / 3, 0.5).asDiagonal();
  k.inertia(0, 1) = k.inertia(1, 0) = 2e-18;  // rounding too
  return k;
}

std::string fixed(const std::string& text, std::string& why) {
  const Model model = load(text);
  const std::vector<FixIt> fixes = link_mass_fixes(text, "fix.body", model.links[0], keys(), why);
  if (fixes.empty()) return {};
  auto result = apply_fixes(text, fixes, why);
  REQUIRE(result);
  return *result;
}

}  // namespace

TEST_CASE("geometry fix: the tensor is written number by number in the file's own layout") {
  std::string why;
  const std::string text = std::string(kHead) + R"(    mass: 8.0
    center_of_mass: [0, 0, 0]
    inertia: [ 0.1, 0,   0,
               0,   0.1, 0,
               0,   0,   0.5 ]
)";
  CHECK(fixed(text, why) == std::string(kHead) + R"(    mass: 8.0
    center_of_mass: [0.1, 0, 0]
    inertia: [ 0.25, 0,   0,
               0,   0.333333333, 0,
               0,   0,   0.5 ]
)");
  // The 6-element form keeps six numbers, a block sequence its lines.
  const std::string six = std::string(kHead) + R"(    mass: 8.0
    center_of_mass:
      - 0
      - 0
      - 0
    inertia: [1, 0, 0, 1, 0, 1]
)";
  CHECK(fixed(six, why) == std::string(kHead) + R"(    mass: 8.0
    center_of_mass:
      - 0.1
      - 0
      - 0
    inertia: [0.25, 0, 0, 0.333333333, 0, 0.5]
)");
}

TEST_CASE("geometry fix: missing keys are inserted before the mass, indented as it is") {
  std::string why;
  const std::string text = std::string(kHead) + "    mass: 8.0\n";
  CHECK(fixed(text, why) == std::string(kHead) + R"(    inertia: [0.25, 0, 0, 0, 0.333333333, 0, 0, 0, 0.5]
    center_of_mass: [0.1, 0, 0]
    mass: 8.0
)");
  // A sequence item's first key keeps its "- ".
  const std::string item =
      std::string(kHead) + "    elements: []\n" + "  - mass: 8.0\n    name: ARM\n    parent: BASE\n";
  const Model model = load(item);
  REQUIRE(model.links.size() == 2);
  const std::vector<FixIt> fixes = link_mass_fixes(item, "fix.body", model.links[1], keys(), why);
  auto result = apply_fixes(item, fixes, why);
  REQUIRE(result);
  CHECK(*result == std::string(kHead) + "    elements: []\n" +
                       "  - inertia: [0.25, 0, 0, 0, 0.333333333, 0, 0, 0, 0.5]\n"
                       "    center_of_mass: [0.1, 0, 0]\n"
                       "    mass: 8.0\n    name: ARM\n    parent: BASE\n");
}

TEST_CASE("geometry fix: nothing is offered for text the edit cannot own") {
  std::string why;
  // The tensor is shared through an alias with another link.
  const std::string aliased = std::string(kHead) + R"(    mass: 8.0
    inertia: &I [1, 0, 0, 0, 1, 0, 0, 0, 1]
  - name: ARM
    parent: BASE
    mass: 1
    inertia: *I
)";
  const Model model = load(aliased);
  CHECK(link_mass_fixes(aliased, "fix.body", model.links[1], keys(), why).empty());
  CHECK(why.find("inertia") != std::string::npos);
  // No mass key: nothing to scale the geometry to.
  const std::string massless = std::string(kHead) + "    inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n";
  CHECK(fixed(massless, why).empty());
  CHECK(why.find("no link-level mass") != std::string::npos);
}
