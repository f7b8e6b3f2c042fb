// Loader unit tests for load/values.cpp: rotation, translation, joint_axis, inertia and
// range syntaxes (body-format-spec §3, §4). Line 1 of every text is `format: ChoreonoidBody`,
// line 2 `format_version: 2.0` (load_v2), so the first line of each snippet is line 3.

#include "support/load_helpers.h"

#include <bodyfmt/angles.h>

#include <cmath>

using bodyfmt::kUnlimited;
using bodyfmt::test::load;
using bodyfmt::test::load_v2;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

namespace {
using bodyfmt::kPi;
constexpr double kEps = 1e-12;

bool near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double eps = kEps) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a - b).cwiseAbs().maxCoeff() <= eps;
}
}  // namespace

TEST_CASE("load: rotation axis-angle is in degrees and the axis is normalised") {
  auto r = load_v2(R"(
links:
  - name: A
    rotation: [0, 0, 2, 90]
)");
  // Rz(90 deg): x -> y, y -> -x.
  Eigen::Matrix3d expected;
  expected << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  CHECK(near(r.link("A").X_PL.linear(), expected));
  r.expect_clean();
}

TEST_CASE("load: rotation list is R1 * R2 (SimpleTank camera)") {
  auto r = load_v2(R"(
links:
  - name: A
    rotation: [[1, 0, 0, 90], [0, 1, 0, -90]]
)");
  // Rx(90) = [1 0 0; 0 0 -1; 0 1 0], Ry(-90) = [0 0 -1; 0 1 0; 1 0 0].
  // Rx(90) * Ry(-90): row1 = (1,0,0) Ry = (0,0,-1); row2 = (0,0,-1) Ry = -(1,0,0) = (-1,0,0);
  // row3 = (0,1,0) Ry = (0,1,0). Same as SimpleTank.ref.yaml's Camera rotation
  // [6e-17, 0, -1, -1, 6e-17, -6e-17, 6e-17, 1, 4e-33].
  Eigen::Matrix3d expected;
  expected << 0, 0, -1, -1, 0, 0, 0, 1, 0;
  CHECK(near(r.link("A").X_PL.linear(), expected));
  r.expect_clean();
}

TEST_CASE("load: translation given as a list of vec3 is summed") {
  auto r = load_v2(R"(
links:
  - name: A
    translation: [[1, 2, 3], [0.5, 0, -1]]
)");
  CHECK(near(r.link("A").X_PL.translation(), Eigen::Vector3d(1.5, 2, 2)));
  r.expect_clean();
}

TEST_CASE("load: a translation sum may hold sums, through an alias too (readTranslation is recursive)") {
  auto r = load_v2(R"(
links:
  - name: A
    translation: &OFFSET [[0.1, 0, 0], [0, 0.2, 0]]
  - name: B
    parent: A
    translation: [ *OFFSET, [-0.012, 0.03, 0.42] ]
  - name: C
    parent: A
    translation: [[1, 0, 0], [[0, 1, 0], [[0, 0, 1], [0, 0, 2]]]]
)");
  // A = (0.1, 0.2, 0); B = A's sum + (-0.012, 0.03, 0.42); C = x + (y + (z + 2z)).
  CHECK(near(r.link("A").X_PL.translation(), Eigen::Vector3d(0.1, 0.2, 0)));
  CHECK(near(r.link("B").X_PL.translation(), Eigen::Vector3d(0.088, 0.23, 0.42), 1e-15));
  CHECK(near(r.link("C").X_PL.translation(), Eigen::Vector3d(1, 1, 3)));
  r.expect_clean();
}

TEST_CASE("load: a term of a translation sum that is no vector is located at the term") {
  auto r = load_v2(R"(
links:
  - name: A
    translation: [[1, 0, 0], [[0, 1], [0, 0, 1]]]
  - name: B
    parent: A
    translation: [[1, 0, 0], 5]
)");
  // Line 5 "    translation: [[1, 0, 0], [[0, 1]," : [0, 1] starts at column 31.
  CHECK(pos(r.take("load-vector-size")) == Pos{5, 31});
  // Line 8: the scalar 5 at column 30 (Choreonoid: "The value is not a listing").
  CHECK(pos(r.take("load-type")) == Pos{8, 30});
  r.expect_clean();
}

TEST_CASE("load: rotation with a zero axis and wrong element count are errors") {
  auto r = load_v2(R"(
links:
  - name: A
    rotation: [0, 0, 0, 90]
  - name: B
    parent: A
    rotation: [1, 0, 0, 0, 1, 0, 0, 0, 1]
)");
  CHECK(pos(r.take("load-rotation-axis")) == Pos{5, 15});
  CHECK(pos(r.take("load-vector-size")) == Pos{8, 15});
  CHECK(r.link("A").X_PL.linear().isIdentity());
  r.expect_clean();
}

TEST_CASE("load: joint_axis symbols in any case, vec3 not normalised, default +Z") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: X1, parent: A, joint_type: revolute, joint_axis: X}
  - {name: Y1, parent: A, joint_type: revolute, joint_axis: -y}
  - {name: Z1, parent: A, joint_type: revolute, joint_axis: -Z}
  - {name: Z2, parent: A, joint_type: revolute, joint_axis: z}
  - {name: V, parent: A, joint_type: revolute, joint_axis: [0, 2, 0]}
  - {name: D, parent: A, joint_type: revolute}
)");
  CHECK(r.link("X1").joint_axis == Eigen::Vector3d(1, 0, 0));
  CHECK(r.link("Y1").joint_axis == Eigen::Vector3d(0, -1, 0));
  CHECK(r.link("Z1").joint_axis == Eigen::Vector3d(0, 0, -1));
  CHECK(r.link("Z2").joint_axis == Eigen::Vector3d(0, 0, 1));
  CHECK(r.link("V").joint_axis == Eigen::Vector3d(0, 2, 0));
  CHECK(r.link("D").joint_axis == Eigen::Vector3d(0, 0, 1));
  r.expect_clean();
}

TEST_CASE("load: illegal joint_axis symbol is load-axis at the value") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
    joint_type: revolute
    joint_axis: W
)");
  auto d = r.take("load-axis");
  CHECK(d.severity == bodyfmt::Severity::kError);
  CHECK(pos(d) == Pos{8, 17});
  CHECK(r.link("B").joint_axis == Eigen::Vector3d(0, 0, 1));
  r.expect_clean();
}

TEST_CASE("load: inertia with 6 elements is the symmetric matrix of the upper triangle") {
  auto r = load_v2(R"(
links:
  - name: A
    mass: 2
    inertia: [1, 0.1, 0.2, 3, 0.3, 5]
)");
  const auto& c = r.link("A").mass_contributions;
  REQUIRE(c.size() == 1);
  Eigen::Matrix3d expected;
  expected << 1, 0.1, 0.2, 0.1, 3, 0.3, 0.2, 0.3, 5;
  CHECK(c[0].inertia == expected);
  CHECK(c[0].mass == 2);
  r.expect_clean();
}

TEST_CASE("load: inertia with 9 elements is row-major, symmetry not enforced") {
  auto r = load_v2(R"(
links:
  - name: A
    mass: 2
    inertia: [1, 2, 3, 4, 5, 6, 7, 8, 9]
)");
  const auto& c = r.link("A").mass_contributions;
  REQUIRE(c.size() == 1);
  Eigen::Matrix3d expected;
  expected << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  CHECK(c[0].inertia == expected);
  r.expect_clean();
}

TEST_CASE("load: inertia with 5 elements is load-inertia-size") {
  auto r = load_v2(R"(
links:
  - name: A
    mass: 2
    inertia: [1, 0, 0, 1, 0]
)");
  auto d = r.take("load-inertia-size");
  CHECK(d.severity == bodyfmt::Severity::kError);
  CHECK(pos(d) == Pos{6, 14});
  // The link-level contribution keeps its default inertia (no RigidBody: identity).
  const auto& c = r.link("A").mass_contributions;
  REQUIRE(c.size() == 1);
  CHECK(c[0].inertia.isIdentity());
  r.expect_clean();
}

TEST_CASE("load: unlimited, scalar and mixed joint ranges") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: U, parent: A, joint_type: revolute, joint_range: unlimited}
  - {name: S, parent: A, joint_type: revolute, joint_range: 45}
  - {name: L, parent: A, joint_type: revolute, joint_range: [unlimited, 30]}
  - {name: H, parent: A, joint_type: revolute, joint_range: [-30, unlimited]}
  - {name: V, parent: A, joint_type: revolute, max_joint_velocity: unlimited}
  - {name: D, parent: A, joint_type: revolute}
)");
  CHECK(r.link("U").joint_range_lower == -kUnlimited);
  CHECK(r.link("U").joint_range_upper == kUnlimited);
  // scalar v -> [-v, v], degrees -> radians.
  CHECK(r.link("S").joint_range_lower == doctest::Approx(-kPi / 4).epsilon(1e-15));
  CHECK(r.link("S").joint_range_upper == doctest::Approx(kPi / 4).epsilon(1e-15));
  CHECK(r.link("L").joint_range_lower == -kUnlimited);
  CHECK(r.link("L").joint_range_upper == doctest::Approx(kPi / 6).epsilon(1e-15));
  CHECK(r.link("H").joint_range_lower == doctest::Approx(-kPi / 6).epsilon(1e-15));
  CHECK(r.link("H").joint_range_upper == kUnlimited);
  CHECK(r.link("V").velocity_lower == -kUnlimited);
  CHECK(r.link("V").velocity_upper == kUnlimited);
  // Absent: unlimited.
  CHECK(r.link("D").joint_range_lower == -kUnlimited);
  CHECK(r.link("D").joint_range_upper == kUnlimited);
  CHECK(r.link("D").velocity_upper == kUnlimited);
  CHECK(r.link("D").effort_upper == kUnlimited);
  r.expect_clean();
}

TEST_CASE("load: joint range syntax errors are load-range at the offending value") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: B, parent: A, joint_type: revolute, joint_range: [-1, abc]}
  - {name: C, parent: A, joint_type: revolute, joint_range: [1, 2, 3]}
  - {name: D, parent: A, joint_type: revolute, joint_range: {lo: 1}}
)");
  // Line 5: "  - {name: B, parent: A, joint_type: revolute, joint_range: [" is 61 chars; "abc"
  // is after "-1, " -> column 62 + 4 = 66.
  CHECK(pos(r.take("load-range")) == Pos{5, 66});
  CHECK(pos(r.take("load-range")) == Pos{6, 61});
  CHECK(pos(r.take("load-range")) == Pos{7, 61});
  CHECK(r.link("B").joint_range_upper == kUnlimited);
  r.expect_clean();
}

TEST_CASE("load: inf in a limit is an open side, as Choreonoid's strtod reads it, with a note") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: P, parent: A, joint_type: revolute, joint_range: [0.0, inf]}
  - {name: Q, parent: A, joint_type: revolute, joint_range: [-inf, 30]}
  - {name: R, parent: A, joint_type: revolute, joint_range: inf}
  - {name: V, parent: A, joint_type: revolute, joint_velocity_range: [-INF, Infinity]}
  - {name: E, parent: A, joint_type: revolute, max_joint_effort: inf}
  - {name: O, parent: A, joint_type: prismatic, joint_range: [0, 1e999]}
)");
  CHECK(r.link("P").joint_range_lower == 0);
  CHECK(r.link("P").joint_range_upper == kUnlimited);
  CHECK(r.link("Q").joint_range_lower == -kUnlimited);
  CHECK(r.link("Q").joint_range_upper == doctest::Approx(kPi / 6).epsilon(1e-15));
  CHECK(r.link("R").joint_range_lower == -kUnlimited);
  CHECK(r.link("R").joint_range_upper == kUnlimited);
  CHECK(r.link("V").velocity_lower == -kUnlimited);
  CHECK(r.link("V").velocity_upper == kUnlimited);
  CHECK(r.link("E").effort_lower == -kUnlimited);
  CHECK(r.link("E").effort_upper == kUnlimited);
  CHECK(r.link("O").joint_range_lower == 0);
  CHECK(r.link("O").joint_range_upper == kUnlimited);
  // One note at each infinite value (columns counted on the lines above), each with a safe
  // fix-it to `unlimited`, the spelling that means the same to Choreonoid.
  for (Pos at : {Pos{5, 67}, Pos{6, 62}, Pos{7, 61}, Pos{8, 71}, Pos{8, 77}, Pos{9, 66}, Pos{10, 66}}) {
    CAPTURE(at);
    auto d = r.take("load-infinite-limit");
    CHECK(pos(d) == at);
    CHECK(d.severity == bodyfmt::Severity::kNote);
    REQUIRE(d.fixes.size() == 1);
    CHECK(d.fixes[0].replacement == "unlimited");
    CHECK(d.fixes[0].safety == bodyfmt::FixSafety::kSafe);
  }
  r.expect_clean();
}

TEST_CASE("load: an infinity on the wrong side gives an empty range and no fix-it") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: X, parent: A, joint_type: revolute, joint_range: [inf, 0]}
)");
  CHECK(r.link("X").joint_range_lower == kUnlimited);
  CHECK(r.link("X").joint_range_upper == 0);
  auto d = r.take("load-infinite-limit");
  CHECK(pos(d) == Pos{5, 62});
  CHECK(d.fixes.empty());
  r.expect_clean();
}

TEST_CASE("load: a limit is read whole, as readLimitValue does: 0.t, .inf and nan are refused") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: B, parent: A, joint_type: revolute, joint_range: [0.t, 1]}
  - {name: C, parent: A, joint_type: revolute, joint_range: [-1, .inf]}
  - {name: D, parent: A, joint_type: revolute, max_joint_velocity: 2rad}
  - {name: N, parent: A, joint_type: revolute, joint_range: [nan, 1]}
)");
  // Choreonoid: "Unknown symbol is used as a jointRange value" (not the lenient prefix 0).
  CHECK(pos(r.take("load-range")) == Pos{5, 62});
  CHECK(pos(r.take("load-range")) == Pos{6, 66});
  CHECK(pos(r.take("load-range")) == Pos{7, 68});
  CHECK(pos(r.take("load-number")) == Pos{8, 62});
  CHECK_FALSE(r.has("load-lenient-number"));
  CHECK(r.link("B").joint_range_lower == -kUnlimited);
  r.expect_clean();
}
