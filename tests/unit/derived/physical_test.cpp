// The physical-validity gate (bodyfmt/physical.h) against a table of mutants: one defect each,
// with the finding and the line it must be reported at, plus valid variants that must pass.
#include <bodyfmt/derived.h>
#include <bodyfmt/physical.h>

#include "support/load_helpers.h"

#include <doctest/doctest.h>

#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using namespace bodyfmt;
using bodyfmt::test::load_v2;

namespace {

// Line 3 of the loaded text is the first line here (load_v2 adds a two-line header).
constexpr const char* kArm = R"(
name: T
root_link: BASE
links:
  - name: BASE
    joint_type: free
    mass: 1
    inertia: [0.015, 0, 0, 0.015, 0, 0.015]
  - name: ARM
    parent: BASE
    joint_type: revolute
    joint_id: 0
    joint_axis: [0, 0, 1]
    joint_range: [-90, 90]
    mass: 0.5
    inertia: [0.002, 0, 0, 0.002, 0, 0.002]
    elements:
      - type: RigidBody
        mass: 0
        inertia: [0, 0, 0, 0, 0, 0]
  - name: HAND
    parent: ARM
    joint_type: fixed
    mass: 0.2
    inertia: [0.001, 0, 0, 0.001, 0, 0.001]
)";
// Lines of kArm after load_v2.
constexpr int kAxisLine = 14, kRangeLine = 15, kMassLine = 16, kInertiaLine = 17, kRigidBodyLine = 19,
              kRigidBodyMassLine = 20, kHandMassLine = 25;

/// kArm with whole lines replaced (the line's key and indentation are kept from `text`).
std::string mutate(const std::map<int, std::string>& lines) {
  std::istringstream in(std::string(kArm).substr(1));
  std::string out, line;
  for (int n = 3; std::getline(in, line); ++n) {
    auto it = lines.find(n);
    out += (it != lines.end() ? it->second : line) + "\n";
  }
  return "\n" + out;
}

using Expected = std::vector<std::tuple<PhysicalDefect, std::string, int>>;  // defect, link, line

struct Mutant {
  const char* what;
  std::map<int, std::string> lines;
  Expected expected;
  PhysicalOptions options = {};
};

std::string describe(const Model& model, const std::vector<PhysicalFinding>& findings) {
  std::string s;
  for (const PhysicalFinding& f : findings)
    s += std::string(f.rule()) + " " + model.links[static_cast<std::size_t>(f.link)].name + " line " +
         std::to_string(f.at.line) + "; ";
  return s;
}

}  // namespace

TEST_CASE("physical: every mutant gives its one finding at its line, every valid variant none") {
  PhysicalOptions balance;
  balance.balance_inertia = true;
  const std::vector<Mutant> mutants = {
      {"valid", {}, {}},
      {"a negative mass key", {{kMassLine, "    mass: -1"}}, {{PhysicalDefect::kNegativeMass, "ARM", kMassLine}}},
      {"a negative RigidBody mass beside a positive mass key: the RigidBody carries the defect",
       {{kRigidBodyMassLine, "        mass: -2"}},
       {{PhysicalDefect::kNegativeMass, "ARM", kRigidBodyLine}}},
      {"a negative principal moment",
       {{kInertiaLine, "    inertia: [0.002, 0, 0, 0.002, 0, -0.001]"}},
       {{PhysicalDefect::kNotPositiveDefinite, "ARM", kInertiaLine}}},
      {"the triangle inequality",
       {{kInertiaLine, "    inertia: [0.001, 0, 0, 0.001, 0, 0.01]"}},
       {{PhysicalDefect::kTriangle, "ARM", kInertiaLine}}},
      {"valid: the triangle inequality with equality (MuJoCo's test has no tolerance)",
       {{kInertiaLine, "    inertia: [0.001, 0, 0, 0.001, 0, 0.002]"}},
       {}},
      {"an asymmetric 9-element tensor",
       {{kInertiaLine, "    inertia: [0.002, 0.001, 0, 0, 0.002, 0, 0, 0, 0.002]"}},
       {{PhysicalDefect::kInertiaAsymmetric, "ARM", kInertiaLine}}},
      {"valid: asymmetric within the tolerance",
       {{kInertiaLine, "    inertia: [0.002, 1e-12, 0, 0, 0.002, 0, 0, 0, 0.002]"}},
       {}},
      {"a moving massless link with a massless fixed child",
       {{kMassLine, "    mass: 0"}, {kInertiaLine, "    inertia: [0, 0, 0, 0, 0, 0]"}, {kHandMassLine, "    mass: 0"}},
       {{PhysicalDefect::kMovingMassless, "ARM", kMassLine}}},
      {"valid: a moving massless link whose fixed child carries mass",
       {{kMassLine, "    mass: 0"}, {kInertiaLine, "    inertia: [0, 0, 0, 0, 0, 0]"}},
       {}},
      {"a moving link below MuJoCo's minimum, its fixed child massless",
       {{kMassLine, "    mass: 1e-16"}, {kHandMassLine, "    mass: 0"}},
       {{PhysicalDefect::kMovingBelowMinimum, "ARM", kInertiaLine}}},
      {"a zero axis", {{kAxisLine, "    joint_axis: [0, 0, 0]"}}, {{PhysicalDefect::kAxisZero, "ARM", kAxisLine}}},
      {"an axis of length 2",
       {{kAxisLine, "    joint_axis: [0, 0, 2]"}},
       {{PhysicalDefect::kAxisNotUnit, "ARM", kAxisLine}}},
      {"valid: an axis of length 1 within 1e-6", {{kAxisLine, "    joint_axis: [0, 0, 1.0000001]"}}, {}},
      {"a reversed range",
       {{kRangeLine, "    joint_range: [10, -10]"}},
       {{PhysicalDefect::kRangeReversed, "ARM", kRangeLine}}},
      {"a zero-width range",
       {{kRangeLine, "    joint_range: [5, 5]"}},
       {{PhysicalDefect::kRangeZeroWidth, "ARM", kRangeLine}}},
      {"under the balancing policy, a balanced tensor is what MuJoCo is given: no moving-body finding",
       {{kInertiaLine, "    inertia: [0.002, 0, 0, 0.002, 0, -0.001]"}, {kHandMassLine, "    mass: 0"}},
       {{PhysicalDefect::kNotPositiveDefinite, "ARM", kInertiaLine}},
       balance},
      {"without it, the negative moment also leaves the moving link below MuJoCo's minimum",
       {{kInertiaLine, "    inertia: [0.002, 0, 0, 0.002, 0, -0.001]"}, {kHandMassLine, "    mass: 0"}},
       {{PhysicalDefect::kNotPositiveDefinite, "ARM", kInertiaLine},
        {PhysicalDefect::kMovingBelowMinimum, "ARM", kInertiaLine}}},
  };
  int detected = 0, defective = 0;
  for (const Mutant& mutant : mutants) {
    CAPTURE(mutant.what);
    auto loaded = load_v2(mutate(mutant.lines));
    const Model& model = loaded.m();
    CollectingSink sink;
    const Derived derived = compute_derived(model, sink);
    const PhysicalVerdict verdict = assess_physical(model, derived, mutant.options);
    CAPTURE(describe(model, verdict.findings));
    Expected got;
    for (const PhysicalFinding& f : verdict.findings) {
      got.emplace_back(f.defect, model.links[static_cast<std::size_t>(f.link)].name, f.at.line);
      CHECK(f.at.column > 0);
    }
    CHECK(got == mutant.expected);
    if (!mutant.expected.empty()) {
      ++defective;
      detected += got == mutant.expected;
    }
  }
  CHECK(detected == defective);
  MESSAGE("gate mutation score: " << detected << " of " << defective << " mutants found at their line");
}

TEST_CASE("physical: what the verdict says a tool may build") {
  SUBCASE("an unphysical inertia makes the masses unusable, unless the policy balances it") {
    auto loaded = load_v2(mutate({{kInertiaLine, "    inertia: [0.001, 0, 0, 0.001, 0, 0.01]"}}));
    const Model& model = loaded.m();
    CollectingSink sink;
    const Derived derived = compute_derived(model, sink);
    const PhysicalVerdict refused = assess_physical(model, derived);
    CHECK_FALSE(refused.masses_usable);
    CHECK_FALSE(refused.links[1].usable);
    REQUIRE(refused.findings.size() == 1);
    CHECK_FALSE(refused.findings[0].balanced_by_policy);
    // The hint's tensor is balance_inertia()'s, under either policy.
    REQUIRE(refused.findings[0].balanced.has_value());
    CHECK(refused.findings[0].balanced->isApprox(*balance_inertia(derived.mass[1].inertia)));
    PhysicalOptions balance;
    balance.balance_inertia = true;
    const PhysicalVerdict balanced = assess_physical(model, derived, balance);
    CHECK(balanced.masses_usable);
    REQUIRE(balanced.findings.size() == 1);
    CHECK(balanced.findings[0].balanced_by_policy);
    CHECK(inertia_validity(principal_inertia(balanced.findings[0].balanced_inertia())).valid());
  }
  SUBCASE("a negative mass is unusable whatever the policy") {
    auto loaded = load_v2(mutate({{kMassLine, "    mass: -1"}}));
    CollectingSink sink;
    const Derived derived = compute_derived(loaded.m(), sink);
    PhysicalOptions balance;
    balance.balance_inertia = true;
    const PhysicalVerdict verdict = assess_physical(loaded.m(), derived, balance);
    CHECK_FALSE(verdict.masses_usable);
    CHECK(verdict.links[1].negative_mass);
  }
  SUBCASE("a zero axis or a reversed range makes the joints unusable; a non-unit axis does not") {
    struct Case {
      int line;
      std::string text;
      bool usable;
    };
    for (const Case& c : std::vector<Case>{{kAxisLine, "    joint_axis: [0, 0, 0]", false},
                                           {kRangeLine, "    joint_range: [10, -10]", false},
                                           {kAxisLine, "    joint_axis: [0, 0, 2]", true},
                                           {kRangeLine, "    joint_range: [5, 5]", true}}) {
      CAPTURE(c.text);
      auto loaded = load_v2(mutate({{c.line, c.text}}));
      CollectingSink sink;
      const Derived derived = compute_derived(loaded.m(), sink);
      CHECK(assess_physical(loaded.m(), derived).joints_usable == c.usable);
      CHECK(assess_joints(loaded.m()).size() == 1);
    }
  }
  SUBCASE("welded to the world: a fixed root and its fixed descendants, not what hangs below a joint") {
    auto loaded = load_v2(mutate({{7, "    joint_type: fixed"}}));
    CollectingSink sink;
    const Derived derived = compute_derived(loaded.m(), sink);
    const PhysicalVerdict verdict = assess_physical(loaded.m(), derived);
    REQUIRE(verdict.links.size() == 3);
    CHECK(verdict.links[0].welded_to_world);
    CHECK_FALSE(verdict.links[1].welded_to_world);  // ARM: revolute
    CHECK_FALSE(verdict.links[2].welded_to_world);  // HAND: fixed to ARM
  }
}
