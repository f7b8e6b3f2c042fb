// Loader unit tests for load/mapping_reader.cpp: legacy spellings and unknown keys
// (body-format-spec §1 key lookup rules, §14, §15).

#include "support/load_helpers.h"

#include <bodyfmt/fix.h>

using bodyfmt::test::load_v2;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

TEST_CASE("load: camelCase legacy key loads with load-legacy-key naming the modern key") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
    jointType: revolute
    jointRange: [-90, 90]
)");
  auto type = r.take("load-legacy-key");
  CHECK(type.severity == bodyfmt::Severity::kWarning);
  CHECK(pos(type) == Pos{7, 5});
  CHECK(type.fix_hint.find("joint_type") != std::string::npos);
  auto range = r.take("load-legacy-key");
  CHECK(pos(range) == Pos{8, 5});
  CHECK(range.fix_hint.find("joint_range") != std::string::npos);
  CHECK(r.link("B").joint_type == bodyfmt::JointType::kRevolute);
  CHECK(r.link("B").joint_range_upper == doctest::Approx(3.14159265358979323846 / 2).epsilon(1e-15));
  r.expect_clean();
}

TEST_CASE("load: snake_case wins over camelCase when both are present") {
  auto r = load_v2(R"(
links:
  - name: A
    joint_type: free
    jointType: fixed
)");
  CHECK(r.link("A").joint_type == bodyfmt::JointType::kFree);
  // The camel spelling stays behind as an unread key: one key written twice.
  CHECK(r.has("load-key-written-twice"));
}

// Issue 47: the hint was "rename it to joint_type", which would write joint_type twice.
// Choreonoid's Mapping::extract({"joint_type", "jointType"}) takes the first spelling present
// in its list, whatever the order in the file: joint_type is read, jointType ignored.
TEST_CASE("load: a key in two spellings is load-key-written-twice, with the edit that removes the ignored one") {
  for (const bool camel_first : {false, true}) {
    CAPTURE(camel_first);
    const std::string snake = "    joint_type: revolute\n";
    const std::string camel = "    jointType: prismatic   # the old spelling\n";
    const std::string text = std::string(
                                 "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: A\n  - name: B\n"
                                 "    parent: A\n") +
                             (camel_first ? camel + snake : snake + camel) + "    joint_axis: Z\n";
    auto r = bodyfmt::test::load(text);
    CHECK(r.link("B").joint_type == bodyfmt::JointType::kRevolute);
    auto d = r.take("load-key-written-twice");
    CHECK(d.severity == bodyfmt::Severity::kWarning);
    CHECK(pos(d) == Pos{camel_first ? 7 : 8, 5});  // the spelling Choreonoid ignores
    CHECK(d.message.find("reads \"joint_type\"") != std::string::npos);
    CHECK(d.message.find("line " + std::to_string(camel_first ? 8 : 7)) != std::string::npos);
    CHECK(d.message.find("rename") == std::string::npos);
    REQUIRE(d.fixes.size() == 1);
    CHECK(d.fixes[0].safety == bodyfmt::FixSafety::kUnsafe);
    std::string why;
    const std::optional<std::string> fixed = bodyfmt::apply_fixes(text, d.fixes, why);
    REQUIRE(fixed);
    CHECK(*fixed == std::string("format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: A\n  - name: B\n"
                                "    parent: A\n    joint_type: revolute\n    joint_axis: Z\n"));
    r.expect_clean();
    auto again = bodyfmt::test::load(*fixed);
    CHECK(again.link("B").joint_type == bodyfmt::JointType::kRevolute);
    again.expect_clean();
  }
}

TEST_CASE("load: a key written twice in a flow mapping or a list item's first line has no edit") {
  auto flow = load_v2(R"(
links:
  - { name: A, joint_type: free, jointType: fixed }
)");
  auto d = flow.take("load-key-written-twice");
  CHECK(pos(d) == Pos{4, 34});
  CHECK(d.fixes.empty());
  flow.expect_clean();
  auto item = load_v2(R"(
links:
  - jointType: fixed
    name: A
    joint_type: free
)");
  auto first = item.take("load-key-written-twice");
  CHECK(pos(first) == Pos{4, 5});
  CHECK(first.fixes.empty());  // removing the line would take the "- " with it
  item.expect_clean();
}

TEST_CASE("load: a misspelt joint_range is load-unknown-model-key, an error with did-you-mean") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
    joint_type: revolute
    jointRnage: [-90, 90]
)");
  auto d = r.take("load-unknown-model-key");
  CHECK(d.severity == bodyfmt::Severity::kError);
  CHECK(pos(d) == Pos{8, 5});  // the key, not the value
  CHECK(d.fix_hint.find("joint_range") != std::string::npos);
  // Ignored: the range stays unlimited.
  CHECK(r.link("B").joint_range_upper == bodyfmt::kUnlimited);
  r.expect_clean();
}

TEST_CASE("load: a snake_case typo of a link key is load-unknown-model-key") {
  auto r = load_v2(R"(
links:
  - name: A
    center_of_mas: [0, 0, 1]
)");
  auto d = r.take("load-unknown-model-key");
  CHECK(pos(d) == Pos{5, 5});
  CHECK(d.fix_hint.find("center_of_mass") != std::string::npos);
  CHECK(r.link("A").mass_contributions.empty());
  r.expect_clean();
}

// The three typos of issue 40: each leaves a default in place (1 kg, an unlimited joint, a joint
// about Z), so each is an error at the key with the key it resembles, snake_case or camelCase.
TEST_CASE("load: typos of keys that change the model are errors naming the key") {
  const struct {
    const char* key;
    const char* meant;
  } typos[] = {{"mas", "mass"},
               {"joint_rnage", "joint_range"},
               {"joint_axsi", "joint_axis"},
               {"jointAxsi", "joint_axis"},
               {"centerOfMas", "center_of_mass"},
               {"inertai", "inertia"},
               {"translaton", "translation"},
               {"rotaton", "rotation"},
               {"max_joint_velocty", "max_joint_velocity"},
               {"maxJointVelocty", "max_joint_velocity"}};
  for (const auto& typo : typos) {
    CAPTURE(typo.key);
    auto r = load_v2(std::string("links:\n  - name: A\n  - name: B\n    parent: A\n    joint_type: revolute\n    ") +
                     typo.key + ": 1\n");
    auto d = r.take("load-unknown-model-key");
    CHECK(d.severity == bodyfmt::Severity::kError);
    CHECK(pos(d) == Pos{8, 5});  // load_v2's two header lines come first
    CHECK(d.message.find(std::string("did you mean \"") + typo.meant + "\"?") != std::string::npos);
    REQUIRE(d.fixes.size() == 1);
    CHECK(d.fixes[0].replacement == typo.meant);
    CHECK(d.fixes[0].safety == bodyfmt::FixSafety::kUnsafe);
    r.expect_clean();
  }
}

TEST_CASE("load: a typo of a key that does not change the model stays a warning") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
    joint_type: revolute
    joint_nmae: J
)");
  auto d = r.take("load-unknown-key");
  CHECK(d.severity == bodyfmt::Severity::kWarning);
  CHECK(d.message.find("joint_name") != std::string::npos);
  r.expect_clean();
}

TEST_CASE("load: a short key two edits from every known key is kept as info") {
  // `ma` is two edits from `mass`: no typo is assumed below the distance the key lengths allow.
  auto r = load_v2(R"(
links:
  - name: A
    ma: 1
    jid: 2
)");
  CHECK(r.take("load-info-key").severity == bodyfmt::Severity::kNote);
  CHECK(r.take("load-info-key").severity == bodyfmt::Severity::kNote);
  r.expect_clean();
}

TEST_CASE("load: an unrelated extra key is kept as info with a note only") {
  auto r = load_v2(R"(
links:
  - name: A
    jointMotorCompliance: 1e-5
)");
  auto d = r.take("load-info-key");
  CHECK(d.severity == bodyfmt::Severity::kNote);
  CHECK(pos(d) == Pos{5, 5});
  r.expect_clean();
}

// MappingReader keeps what it consumed in one inline word up to 64 keys and in a vector
// beyond: a key at either side of that boundary must be read, and every other one reported.
TEST_CASE("load: mappings of 64 and of 65 keys read the last key and report each unread one") {
  for (int extras : {62, 63}) {
    CAPTURE(extras);
    std::string text = "links:\n  - name: A\n";
    for (int i = 0; i < extras; ++i) text += "    kept_as_information_" + std::to_string(i) + ": 1\n";
    text += "    mass: 2.5\n";  // the mapping's entry 63 (inline bit 63), or 64 (the vector)
    auto r = load_v2(text);
    REQUIRE(r.link("A").mass_contributions.size() == 1);
    CHECK(r.link("A").mass_contributions[0].mass == 2.5);
    int reported = 0;
    while (r.has("load-info-key")) {
      auto d = r.take("load-info-key");
      CHECK(d.message.find("mass") == std::string::npos);
      ++reported;
    }
    CHECK(reported == extras);
    r.expect_clean();  // nor is "mass" reported as a misspelling of itself
  }
}
