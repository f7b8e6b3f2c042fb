// Loader unit tests for load/link_reader.cpp: joint keys and their angle conversion
// (body-format-spec §3, §6.1) and link-level mass keys combined with RigidBody contributions
// (§6.4). Lines 1-2 are the header written by load_v2.

#include "support/load_helpers.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/derived.h>

#include <cmath>

using bodyfmt::JointType;
using bodyfmt::kUnlimited;
using bodyfmt::test::load;
using bodyfmt::test::load_v2;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

namespace {
using bodyfmt::kPi;
constexpr double kDeg = kPi / 180;

bool near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double eps = 1e-12) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a - b).cwiseAbs().maxCoeff() <= eps;
}
}  // namespace

TEST_CASE("load: angles default to degrees for revolute limits and joint_angle") {
  auto r = load_v2(R"(
links:
  - name: A
    joint_type: free
  - name: B
    parent: A
    joint_type: revolute
    joint_range: [-30, 60]
    max_joint_velocity: 90
    joint_angle: 45
)");
  CHECK(r.m().angles_in_degrees);
  const auto& b = r.link("B");
  CHECK(b.joint_range_lower == doctest::Approx(-30 * kDeg).epsilon(1e-15));
  CHECK(b.joint_range_upper == doctest::Approx(60 * kDeg).epsilon(1e-15));
  CHECK(b.velocity_lower == doctest::Approx(-90 * kDeg).epsilon(1e-15));
  CHECK(b.velocity_upper == doctest::Approx(90 * kDeg).epsilon(1e-15));
  CHECK(b.initial_displacement == doctest::Approx(45 * kDeg).epsilon(1e-15));
  r.expect_clean();
}

TEST_CASE("load: angle_unit radian in format 1.0 reads angles as radians") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 1.0
angle_unit: radian
links:
  - name: A
  - name: B
    parent: A
    jointType: revolute
    jointRange: [-0.5, 1.5]
    maxJointVelocity: 2
    jointAngle: 0.25
    rotation: [0, 0, 1, 1.0]
)");
  r.diagnostics.clear();  // legacy-key warnings are covered elsewhere
  CHECK_FALSE(r.m().angles_in_degrees);
  const auto& b = r.link("B");
  CHECK(b.joint_range_lower == -0.5);
  CHECK(b.joint_range_upper == 1.5);
  CHECK(b.velocity_upper == 2);
  CHECK(b.initial_displacement == 0.25);
  CHECK(near(b.X_PL.linear(), Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
}

TEST_CASE("load: limits of non-revolute joints are not angle-converted") {
  // The joint type is read first, so joint_range before joint_type is still converted for B.
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
    joint_range: [-30, 60]
    joint_type: revolute
  - name: P
    parent: A
    joint_type: prismatic
    joint_range: [-0.1, 0.2]
    max_joint_velocity: 0.5
  - name: T
    parent: A
    joint_type: pseudo_continuous_track
    max_joint_velocity: 2
  - name: R
    parent: A
    joint_type: revolute
    joint_velocity_range: [-30, 60]
)");
  CHECK(r.link("B").joint_range_lower == doctest::Approx(-30 * kDeg).epsilon(1e-15));
  CHECK(r.link("B").joint_range_upper == doctest::Approx(60 * kDeg).epsilon(1e-15));
  const auto& p = r.link("P");
  CHECK(p.joint_type == JointType::kPrismatic);
  CHECK(p.joint_range_lower == -0.1);
  CHECK(p.joint_range_upper == 0.2);
  CHECK(p.velocity_lower == -0.5);
  CHECK(p.velocity_upper == 0.5);
  const auto& t = r.link("T");
  CHECK(t.joint_type == JointType::kPseudoContinuousTrack);
  CHECK(t.velocity_lower == -2);  // m/s, not converted
  CHECK(t.velocity_upper == 2);
  CHECK(r.link("R").velocity_lower == doctest::Approx(-30 * kDeg).epsilon(1e-15));
  CHECK(r.link("R").velocity_upper == doctest::Approx(60 * kDeg).epsilon(1e-15));
  r.expect_clean();
}

TEST_CASE("load: joint_velocity_range is ignored when max_joint_velocity is given") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
    joint_type: revolute
    max_joint_velocity: 90
    joint_velocity_range: [-10, 10]
)");
  CHECK(pos(r.take("load-ignored-key")) == Pos{9, 27});
  CHECK(r.link("B").velocity_upper == doctest::Approx(90 * kDeg).epsilon(1e-15));
  CHECK(r.link("B").velocity_lower == doctest::Approx(-90 * kDeg).epsilon(1e-15));
  r.expect_clean();
}

TEST_CASE("load: joint_angle is always converted, joint_displacement only for revolute and wins") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: P1
    parent: A
    joint_type: prismatic
    joint_angle: 90
  - name: P2
    parent: A
    joint_type: prismatic
    joint_displacement: 0.25
  - name: R1
    parent: A
    joint_type: revolute
    joint_displacement: 30
  - name: R2
    parent: A
    joint_type: revolute
    joint_angle: 10
    joint_displacement: 20
  - name: F
    parent: A
    joint_angle: 180
)");
  // joint_angle on a prismatic joint: 90 "degrees" -> pi/2 metres, with a warning.
  CHECK(r.link("P1").initial_displacement == doctest::Approx(kPi / 2).epsilon(1e-15));
  CHECK(pos(r.take("load-angle-on-prismatic")) == Pos{8, 18});
  CHECK(r.link("P2").initial_displacement == 0.25);
  CHECK(r.link("R1").initial_displacement == doctest::Approx(30 * kDeg).epsilon(1e-15));
  CHECK(r.link("R2").initial_displacement == doctest::Approx(20 * kDeg).epsilon(1e-15));
  CHECK(r.link("F").initial_displacement == doctest::Approx(kPi).epsilon(1e-15));
  r.expect_clean();
}

TEST_CASE("load: joint_type values, legacy slide and illegal values") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: S, parent: A, joint_type: slide}
  - {name: C, parent: A, joint_type: continuous}
  - {name: F, parent: A}
)");
  CHECK(r.link("S").joint_type == JointType::kPrismatic);
  CHECK(pos(r.take("load-legacy-key")) == Pos{5, 38});
  auto d = r.take("load-joint-type");
  CHECK(d.severity == bodyfmt::Severity::kError);
  CHECK(pos(d) == Pos{6, 38});
  CHECK(r.link("C").joint_type == JointType::kFixed);
  CHECK(r.link("F").joint_type == JointType::kFixed);
  r.expect_clean();
}

TEST_CASE("load: equivalent rotor inertia from gear_ratio and rotor_inertia") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: G, parent: A, joint_type: revolute, rotor_inertia: 0.5, gear_ratio: 3}
  - {name: J, parent: A, joint_type: revolute, joint_axis_inertia: 2, rotor_inertia: 9}
  - {name: E, parent: A, joint_type: revolute, max_joint_effort: 40}
)");
  CHECK(r.link("G").joint_axis_inertia == 4.5);  // 3^2 * 0.5
  CHECK(r.link("J").joint_axis_inertia == 2);    // joint_axis_inertia wins
  CHECK(r.link("E").effort_lower == -40);        // N*m, never converted
  CHECK(r.link("E").effort_upper == 40);
  r.expect_clean();
}

TEST_CASE("load: rotor_inertia and gear_ratio are read whole with defaults, joint_axis_inertia by its prefix") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: G, parent: A, joint_type: revolute, rotor_inertia: 0.5, gear_ratio: 100:1}
  - {name: R, parent: A, joint_type: revolute, rotor_inertia: [1e-4], gear_ratio: 3}
  - {name: J, parent: A, joint_type: revolute, joint_axis_inertia: 2.5kg}
)");
  // Choreonoid (StdBodyLoader, Mapping::get / read): gear 100:1 is no number, so Ir = 0.5 and
  // not 100^2 * 0.5; a list as rotor inertia is ignored (0); joint_axis_inertia is toDouble.
  CHECK(r.link("G").joint_axis_inertia == 0.5);
  CHECK(r.link("R").joint_axis_inertia == 0);
  CHECK(r.link("J").joint_axis_inertia == 2.5);
  CHECK(pos(r.take("load-ignored-value")) == Pos{5, 80});
  CHECK(pos(r.take("load-ignored-value")) == Pos{6, 63});
  CHECK(pos(r.take("load-lenient-number")) == Pos{7, 68});
  r.expect_clean();
}

// ---------------------------------------------------------------------------------------
// Mass combination (§6.4)

TEST_CASE("load: mass combination, SimpleTank TURRET_P worked example") {
  auto r = load_v2(R"(
links:
  - name: TURRET_P
    elements:
      - type: RigidBody
        mass: 3
        inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]
      - type: Transform
        translation: [0.2, 0, 0]
        rotation: [0, 0, 1, 90]
        elements:
          - type: RigidBody
            mass: 1
            inertia: [0.01, 0, 0, 0, 0.1, 0, 0, 0, 0.1]
)");
  // Gun inertia rotated by Rz(90): diag(.1, .01, .1), at c = (0.2, 0, 0).
  // M = 4, C = (3*0 + 1*0.2)/4 = (0.05, 0, 0).
  // Parallel axis, G(d) = |d|^2 1 - d d^T = |d|^2 diag(0,1,1) for d along x:
  //   turret d = 0.05 -> 3*0.0025 = 0.0075; gun d = -0.15 -> 1*0.0225 = 0.0225.
  // Ixx = .1 + .1 = .2; Iyy = .1 + .01 + .0075 + .0225 = .14; Izz = .1 + .1 + .03 = .23.
  const auto mp = bodyfmt::compute_mass_properties(r.link("TURRET_P"));
  CHECK(mp.mass == doctest::Approx(4).epsilon(1e-15));
  CHECK(near(mp.center_of_mass, Eigen::Vector3d(0.05, 0, 0)));
  CHECK(near(mp.inertia, Eigen::Vector3d(0.2, 0.14, 0.23).asDiagonal().toDenseMatrix()));
  r.expect_clean();
}

TEST_CASE("load: mass alone gives identity inertia and zero centre of mass") {
  auto r = load_v2(R"(
links:
  - name: A
    mass: 5
)");
  const auto mp = bodyfmt::compute_mass_properties(r.link("A"));
  CHECK(mp.mass == 5);
  CHECK(mp.center_of_mass == Eigen::Vector3d::Zero());
  CHECK(mp.inertia == Eigen::Matrix3d::Identity());
  r.expect_clean();
}

TEST_CASE("load: a link without mass data gets 1 kg and identity inertia") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Box, size: [1, 2, 3]}
)");
  CHECK(r.link("A").mass_contributions.empty());
  const auto mp = bodyfmt::compute_mass_properties(r.link("A"));
  CHECK(mp.mass == 1);
  CHECK(mp.center_of_mass == Eigen::Vector3d::Zero());
  CHECK(mp.inertia == Eigen::Matrix3d::Identity());
  r.expect_clean();
}

TEST_CASE("load: link keys next to a RigidBody default missing keys to 0, not the Link defaults") {
  auto r = load_v2(R"(
links:
  - name: A
    mass: 2
    center_of_mass: [0, 0, 1]
    elements:
      - type: RigidBody
        mass: 2
        inertia: [0.1, 0, 0, 0.1, 0, 0.1]
)");
  // Link-level inertia is absent -> 0 (not identity). C = (0, 0, 0.5).
  // RigidBody: 0.1*1 + 2*0.25*diag(1,1,0) = diag(.6,.6,.1); link keys: 2*0.25*diag(1,1,0)
  // = diag(.5,.5,0). Sum diag(1.1, 1.1, 0.1) (identity would have given diag(2.1,2.1,1.1)).
  const auto& link = r.link("A");
  REQUIRE(link.mass_contributions.size() == 2);
  const auto mp = bodyfmt::compute_mass_properties(link);
  CHECK(mp.mass == 4);
  CHECK(near(mp.center_of_mass, Eigen::Vector3d(0, 0, 0.5)));
  CHECK(near(mp.inertia, Eigen::Vector3d(1.1, 1.1, 0.1).asDiagonal().toDenseMatrix()));
  r.expect_clean();
}

TEST_CASE("load: link center_of_mass alone defaults mass to 1 and inertia to identity") {
  auto r = load_v2(R"(
links:
  - name: A
    center_of_mass: [0, 0, 1]
)");
  const auto mp = bodyfmt::compute_mass_properties(r.link("A"));
  CHECK(mp.mass == 1);
  CHECK(mp.center_of_mass == Eigen::Vector3d(0, 0, 1));
  CHECK(mp.inertia == Eigen::Matrix3d::Identity());
  r.expect_clean();
}

TEST_CASE("load: mass keys on a Transform are ignored with load-mass-ignored") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Transform
        translation: [1, 0, 0]
        mass: 1.0
        centerOfMass: [0, 0, 0]
        elements:
          - type: RigidBody
            mass: 3
)");
  CHECK(pos(r.take("load-mass-ignored")) == Pos{8, 15});
  r.take("load-legacy-key");  // centerOfMass, at 9:23
  CHECK(pos(r.take("load-mass-ignored")) == Pos{9, 23});
  const auto mp = bodyfmt::compute_mass_properties(r.link("A"));
  CHECK(mp.mass == 3);
  CHECK(mp.center_of_mass == Eigen::Vector3d(1, 0, 0));
  CHECK(mp.inertia == Eigen::Matrix3d::Zero());
  r.expect_clean();
}

TEST_CASE("load: a scaled and rotated RigidBody transforms c as a point and I as L I L^T") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: RigidBody
        translation: [0, 0, 1]
        rotation: [0, 0, 1, 90]
        scale: [2, 1, 1]
        center_of_mass: [0.1, 0.2, 0]
        mass: 1
        inertia: [1, 0, 0, 2, 0, 3]
)");
  // L = Rz(90) diag(2,1,1) = [0 -1 0; 2 0 0; 0 0 1].
  // c' = L (0.1, 0.2, 0) + (0, 0, 1) = (-0.2, 0.2, 1).
  // I' = L diag(1,2,3) L^T = diag(2, 4, 3).
  const auto& c = r.link("A").mass_contributions;
  REQUIRE(c.size() == 1);
  CHECK(near(c[0].center_of_mass, Eigen::Vector3d(-0.2, 0.2, 1)));
  CHECK(near(c[0].inertia, Eigen::Vector3d(2, 4, 3).asDiagonal().toDenseMatrix()));
  CHECK(c[0].mass == 1);
  const auto mp = bodyfmt::compute_mass_properties(r.link("A"));
  CHECK(near(mp.center_of_mass, Eigen::Vector3d(-0.2, 0.2, 1)));
  CHECK(near(mp.inertia, Eigen::Vector3d(2, 4, 3).asDiagonal().toDenseMatrix()));
  r.expect_clean();
}

TEST_CASE("load: a total mass of 0 gives c = 0 and I = 0") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: RigidBody
        center_of_mass: [1, 2, 3]
        inertia: [1, 0, 0, 1, 0, 1]
)");
  const auto mp = bodyfmt::compute_mass_properties(r.link("A"));
  CHECK(mp.mass == 0);
  CHECK(mp.center_of_mass == Eigen::Vector3d::Zero());
  CHECK(mp.inertia == Eigen::Matrix3d::Zero());
  r.expect_clean();
}

TEST_CASE("load: joint_angle is read even where joint_displacement replaces it, and import items are mappings") {
  auto r = load_v2(R"(
links:
  - name: A
    import: [base_info, {x: 1}]
  - {name: B, parent: A, joint_type: revolute, joint_angle: abc, joint_displacement: 10}
)");
  // StdBodyLoader: joint_angle's toDouble throws before joint_displacement is read; an import
  // list's items go through toMapping, which throws on a scalar.
  CHECK(pos(r.take("load-type")) == Pos{5, 14});
  CHECK(pos(r.take("load-number")) == Pos{6, 61});
  CHECK(r.link("B").initial_displacement == doctest::Approx(M_PI / 18).epsilon(1e-15));
  r.expect_clean();
}
