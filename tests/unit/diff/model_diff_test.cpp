// diff_models and canonical_text (bodyfmt/model_diff.h) on inline models: the tolerance on both
// sides of its boundary, locations on both sides, what counts as one change, and the canonical
// text's independence from spelling and link order.
#include <bodyfmt/load.h>
#include <bodyfmt/model_diff.h>

#include <doctest/doctest.h>

#include <string>

namespace {

using namespace bodyfmt;

Model load(const std::string& text, const std::string& name = "x.body") {
  CollectingSink sink;
  LoadOptions options;
  options.load_meshes = false;
  auto model = load_body_string(text, name, options, sink);
  REQUIRE(model);
  return *model;
}

std::string arm(const std::string& mass = "2.0", const std::string& range = "[ -90, 90 ]",
                const std::string& extra = "") {
  return "format: ChoreonoidBody\nformat_version: 2.0\nname: arm\nlinks:\n"
         "  - name: BASE\n    joint_type: fixed\n    mass: 10\n"
         "  - name: ARM\n    parent: BASE\n    translation: [ 0, 0, 0.5 ]\n    joint_type: revolute\n"
         "    joint_axis: Y\n    joint_range: " +
         range + "\n    mass: " + mass + "\n" + extra;
}

std::vector<ModelChange> own(const std::vector<ModelChange>& changes) {
  std::vector<ModelChange> out;
  for (const ModelChange& c : changes)
    if (!c.derived) out.push_back(c);
  return out;
}

}  // namespace

TEST_CASE("the same model has no change, and a mass change is one change at its line on both sides") {
  CHECK(diff_models(load(arm()), load(arm())).empty());
  const auto changes = diff_models(load(arm(), "old.body"), load(arm("2.5"), "new.body"));
  const auto mine = own(changes);
  REQUIRE(mine.size() == 1);
  CHECK(mine[0].kind == ChangeKind::kChanged);
  CHECK(mine[0].link == "ARM");
  CHECK(mine[0].field == "mass");
  CHECK(mine[0].old_value == "2");
  CHECK(mine[0].new_value == "2.5");
  CHECK(mine[0].old_source.file == "old.body");
  CHECK(mine[0].new_source.file == "new.body");
  CHECK(mine[0].old_source.line == 14);
  CHECK(mine[0].new_source.line == 14);
  // total mass 12 -> 12.5 and the centre of mass move with it
  int derived = 0;
  for (const ModelChange& c : changes) derived += c.derived;
  CHECK(derived == 2);
}

TEST_CASE("the tolerance: a change just inside is none, just outside is one") {
  ModelDiffOptions options;
  options.tolerance = 1e-6;
  // relative above 1: 2 * 1e-6 = 2e-6 is the margin
  CHECK(diff_models(load(arm("2.0")), load(arm("2.0000019")), options).empty());
  CHECK(own(diff_models(load(arm("2.0")), load(arm("2.0000021")), options)).size() == 1);
  options.tolerance = 0;
  CHECK(own(diff_models(load(arm("2.0")), load(arm("2.0000000001")), options)).size() == 1);
  options.derived = false;
  CHECK(diff_models(load(arm("2.0")), load(arm("2.5")), options).size() == 1);
}

TEST_CASE("spelling and link order are no change, added and removed links are one change each") {
  std::string legacy = arm();
  legacy.replace(legacy.find("joint_range"), 11, "jointRange");
  CHECK(diff_models(load(arm()), load(legacy)).empty());
  CHECK(canonical_text(load(arm())) == canonical_text(load(legacy)));

  const std::string hand = "  - name: HAND\n    parent: ARM\n    joint_type: fixed\n    mass: 1\n";
  const auto added = own(diff_models(load(arm()), load(arm("2.0", "[ -90, 90 ]", hand))));
  REQUIRE(added.size() == 1);
  CHECK(added[0].kind == ChangeKind::kAdded);
  CHECK(added[0].field == "link");
  CHECK(added[0].link == "HAND");
  CHECK(added[0].new_source.line == 15);
  CHECK(added[0].old_value.empty());
  const auto removed = own(diff_models(load(arm("2.0", "[ -90, 90 ]", hand)), load(arm())));
  REQUIRE(removed.size() == 1);
  CHECK(removed[0].kind == ChangeKind::kRemoved);
  CHECK(removed[0].old_source.line == 15);
}

TEST_CASE("a joint range is compared in radians and shown in degrees too, the world frame moves") {
  const auto changes = diff_models(load(arm("2.0", "[ -90, 90 ]")), load(arm("2.0", "[ -45, 90 ]")));
  REQUIRE(changes.size() == 1);
  CHECK(changes[0].field == "joint_range");
  CHECK(changes[0].new_value.find("[-45, 90] deg") != std::string::npos);

  std::string moved = arm();
  moved.replace(moved.find("[ 0, 0, 0.5 ]"), 13, "[ 0, 0, 0.7 ]");
  bool frame = false;
  for (const ModelChange& c : diff_models(load(arm()), load(moved)))
    if (c.field == "world_frame" && c.link == "ARM") {
      frame = true;
      CHECK(c.derived);
      const auto at = c.new_value.find("(moved ");
      REQUIRE(at != std::string::npos);
      CHECK(std::stod(c.new_value.substr(at + 7)) == doctest::Approx(0.2).epsilon(1e-12));
      CHECK(c.new_value.find("turned 0 deg") != std::string::npos);
    }
  CHECK(frame);
}

TEST_CASE("shapes pair by content: reordered is no change, inserted is one shape added") {
  const std::string box = "      - { type: Shape, geometry: { type: Box, size: [ 1, 2, 3 ] } }\n";
  const std::string ball = "      - { type: Shape, geometry: { type: Sphere, radius: 0.5 } }\n";
  const std::string can = "      - { type: Shape, geometry: { type: Cylinder, radius: 0.1, height: 1 } }\n";
  auto with = [&](const std::string& shapes) { return load(arm("2.0", "[ -90, 90 ]", "    elements:\n" + shapes)); };
  CHECK(diff_models(with(box + ball), with(ball + box)).empty());
  const auto inserted = diff_models(with(box + ball), with(can + box + ball));
  REQUIRE(inserted.size() == 1);
  CHECK(inserted[0].kind == ChangeKind::kAdded);
  CHECK(inserted[0].field == "shape 2");
  CHECK(inserted[0].new_value == "Cylinder");
  CHECK(inserted[0].new_source.line == 16);
  // a changed shape stays paired with the one at its rank
  const auto all =
      diff_models(with(box + ball), with(box + "      - { type: Shape, geometry: { type: Sphere, radius: 0.6 } }\n"));
  const auto resized = own(all);
  REQUIRE(resized.size() == 1);
  CHECK(resized[0].field == "shape 1 radius");
  // and the link's boxes (visual and collision alike) widen in x only: the 1 x 2 x 3 box's
  // half-sizes against the sphere's radius, 0.5 then 0.6
  REQUIRE(all.size() == 3);
  for (const ModelChange& c : all) {
    if (!c.derived) continue;
    CHECK((c.field == "visual_bounding_box" || c.field == "collision_bounding_box"));
    CHECK(c.old_value == "min [-0.5, -1, -1.5] max [0.5, 1, 1.5]");
    CHECK(c.new_value == "min [-0.6, -1, -1.5] max [0.6, 1, 1.5]");
  }
}
