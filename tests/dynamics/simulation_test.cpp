// The Simbody system built from a model (dynamics/): mass properties, mobilizers, gravity, the
// belt direction and the inertia policy, each against numbers worked out by hand or from
// textbook formulas written out here, not from Simbody.
#include <doctest/doctest.h>

#include <bodyfmt/dynamics/checks.h>
#include <bodyfmt/dynamics/simulation.h>
#include <bodyfmt/inertia.h>
#include <bodyfmt/load.h>

#include <cmath>

using namespace bodyfmt;
using namespace bodyfmt::dynamics;

namespace {

struct Built {
  Model model;
  Derived derived;
  std::unique_ptr<Simulation> sim;
  CollectingSink sink;
};

std::unique_ptr<Built> build(const std::string& text, SimOptions options = {}) {
  auto b = std::make_unique<Built>();
  std::optional<Model> model = load_body_string(text, "test.body", LoadOptions{}, b->sink);
  REQUIRE(model);
  b->model = std::move(*model);
  b->derived = compute_derived(b->model, b->sink);
  b->sim = Simulation::build(b->model, b->derived, options, b->sink);
  return b;
}

const char* kFreeBody = R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
links:
  - name: BODY
    joint_type: free
    translation: [0, 0, 1]
    mass: 2.0
    center_of_mass: [0.1, -0.2, 0.05]
    inertia: [0.3, 0.01, 0, 0.01, 0.4, 0, 0, 0, 0.5]
)";

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& c) {
  Eigen::Matrix3d m;
  m << 0, -c.z(), c.y(), c.z(), 0, -c.x(), -c.y(), c.x(), 0;
  return m;
}

SimOptions no_contact() {
  SimOptions o;
  o.contact = false;
  return o;
}

}  // namespace

TEST_CASE("dynamics: a free body's 6x6 mass matrix is the rigid-body one about its origin") {
  auto b = build(kFreeBody, no_contact());
  REQUIRE(b->sim);
  CHECK(b->sim->total_mass() == doctest::Approx(2.0).epsilon(1e-12));
  CHECK((b->sim->center_of_mass() - Eigen::Vector3d(0.1, -0.2, 1.05)).norm() < 1e-12);
  // T = ½ m |v − [c]× ω|² + ½ ωᵀ I_c ω with u = [ω, v] (Simbody's Free mobilizer, world axes).
  const double m = 2;
  const Eigen::Vector3d c(0.1, -0.2, 0.05);
  Eigen::Matrix3d Ic;
  Ic << 0.3, 0.01, 0, 0.01, 0.4, 0, 0, 0, 0.5;
  Eigen::MatrixXd expected(6, 6);
  expected.block<3, 3>(0, 0) = Ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  expected.block<3, 3>(0, 3) = m * cross_matrix(c);
  expected.block<3, 3>(3, 0) = -m * cross_matrix(c);
  expected.block<3, 3>(3, 3) = m * Eigen::Matrix3d::Identity();
  const Eigen::MatrixXd M = b->sim->mass_matrix();
  REQUIRE(M.rows() == 6);
  CHECK((M - expected).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("dynamics: free fall without contact follows z0 - g t^2 / 2 and keeps the orientation") {
  SimOptions options = no_contact();
  options.accuracy = 1e-9;
  auto b = build(kFreeBody, options);
  REQUIRE(b->sim);
  const double z0 = b->sim->center_of_mass().z();
  b->sim->advance_to(0.5);
  CHECK(b->sim->center_of_mass().z() == doctest::Approx(z0 - 0.5 * 9.80665 * 0.25).epsilon(1e-9));
  CHECK(b->sim->link_pose(0).linear().isIdentity(1e-9));
}

TEST_CASE("dynamics: a Pin about a skew, unnormalised axis: inertia about the axis and right-handed motion") {
  auto b = build(R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
links:
  - name: BASE
    joint_type: fixed
    translation: [0, 0, 1]
    mass: 1.0
  - name: ARM
    parent: BASE
    translation: [0.1, 0.2, 0.3]
    joint_type: revolute
    joint_axis: [1, 1, 0]
    mass: 1.5
    center_of_mass: [0, 0, -0.4]
    inertia: [0.02, 0, 0, 0, 0.03, 0, 0, 0, 0.04]
)",
                 no_contact());
  REQUIRE(b->sim);
  const LinkIndex arm = 1;
  REQUIRE(b->sim->has_joint(arm));
  // a = (1, 1, 0)/√2: aᵀ I a = (0.02 + 0.03)/2 = 0.025; the COM is 0.4 m off the axis:
  // 1.5 · 0.16 = 0.24. Total 0.265 kg·m².
  const Eigen::MatrixXd M = b->sim->mass_matrix();
  REQUIRE(M.rows() == 1);
  CHECK(M(0, 0) == doctest::Approx(0.265).epsilon(1e-12));
  CHECK(subtree_axis_inertia(b->model, b->derived, arm, {}) == doctest::Approx(0.265).epsilon(1e-12));
  b->sim->set_joint_position(arm, 0.7);
  const Eigen::Isometry3d X = b->sim->link_pose(arm);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  CHECK((X.linear() - R).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((X.translation() - Eigen::Vector3d(0.1, 0.2, 1.3)).norm() < 1e-12);
  // At q = 90° about a, the COM (0, 0, −0.4) swings to 0.4·(a × −z)... its gravity torque
  // about +a is −m g · (horizontal lever) = −1.5 · 9.80665 · 0.4.
  std::vector<double> q = {0, M_PI / 2};
  CHECK(subtree_gravity_torque(b->model, b->derived, arm, q, 9.80665) ==
        doctest::Approx(-1.5 * 9.80665 * 0.4).epsilon(1e-12));
}

TEST_CASE("dynamics: a Slider carries its welded child, a prismatic q moves along the axis") {
  auto b = build(R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
links:
  - name: BASE
    joint_type: fixed
    mass: 1.0
  - name: CARRIAGE
    parent: BASE
    joint_type: prismatic
    joint_axis: Z
    mass: 0.5
  - name: LOAD
    parent: CARRIAGE
    joint_type: fixed
    translation: [0.3, 0, 0]
    mass: 0.25
)",
                 no_contact());
  REQUIRE(b->sim);
  const Eigen::MatrixXd M = b->sim->mass_matrix();
  REQUIRE(M.rows() == 1);
  CHECK(M(0, 0) == doctest::Approx(0.75).epsilon(1e-12));
  b->sim->set_joint_position(1, 0.2);
  CHECK((b->sim->link_pose(2).translation() - Eigen::Vector3d(0.3, 0, 0.2)).norm() < 1e-12);
}

TEST_CASE("dynamics: an unphysical inertia is refused with the inertia rule, or balanced on request") {
  const std::string text = R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
links:
  - name: CHASSIS
    joint_type: free
    mass: 8.0
    inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.5]
)";
  auto refused = build(text);
  CHECK(refused->sim == nullptr);
  CHECK(refused->sink.has("inertia-triangle"));
  SimOptions options;
  options.balance_inertia = true;
  auto balanced = build(text, options);
  REQUIRE(balanced->sim);
  CHECK(balanced->sink.has("dynamics-inertia-balanced"));
  Eigen::Matrix3d given = Eigen::Vector3d(0.1, 0.1, 0.5).asDiagonal();
  const std::optional<Eigen::Matrix3d> expected = balance_inertia(given);
  REQUIRE(expected);
  CHECK((balanced->sim->link_inertias()[0] - *expected).cwiseAbs().maxCoeff() < 1e-15);
  // The projection onto A + B = C moves each moment by (C − A − B)/3 = 0.1.
  CHECK(balanced->sim->link_inertias()[0](2, 2) == doctest::Approx(0.4).epsilon(1e-6));
}

TEST_CASE("dynamics: +dq on a track drives along a_w × z, also when the vehicle is turned 90°") {
  const std::string path = std::string(BODYFMT_EXAMPLES_DIR) + "/scouttank.body";
  CollectingSink sink;
  std::optional<Model> model = load_body(path, LoadOptions{}, sink);
  REQUIRE(model);
  const Derived derived = compute_derived(*model, sink);
  std::unique_ptr<Simulation> sim = Simulation::build(*model, derived, SimOptions{}, sink);
  REQUIRE(sim);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(0, 0, 0.12);
  sim->set_root_pose(X);
  // Both belts' axes are +Y: a × z = +X of the hull, which now points along world +Y.
  sim->set_track_speed(model->find_link("BELT_B"), 0.5);
  sim->set_track_speed(model->find_link("BELT_A"), 0.5);
  sim->advance_to(2.0);
  const auto [omega, v] = sim->link_velocity(0);
  CHECK(v.y() == doctest::Approx(0.5).epsilon(0.01));
  CHECK(std::abs(v.x()) < 0.005);
  CHECK(std::abs(omega.z()) < 1e-3);
}

TEST_CASE(
    "dynamics: a joint stop holds with stop_stiffness, at most I·ω² under stop_frequency_limit, at least "
    "I·ω² under stop_frequency_floor") {
  // ARM turns about Z (no gravity torque) with the COM 0.1 m off the axis: I = 0.01 + 1 · 0.1² =
  // 0.02 kg·m² about the axis. A constant 18 N·m pushes it into its +10° stop, a damper settles
  // it: at rest the stop pushes back k·x = 18 N·m, so x = 18/k past the limit.
  const std::string text = R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
links:
  - name: BASE
    joint_type: fixed
    mass: 1.0
  - name: ARM
    parent: BASE
    joint_type: revolute
    joint_axis: Z
    joint_range: [-10, 10]
    mass: 1.0
    center_of_mass: [0.1, 0, 0]
    inertia: [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
)";
  const double limit = 10 * M_PI / 180, torque = 18;
  for (const double omega : {0.0, 300.0, 1000.0, -1000.0}) {
    SimOptions o = no_contact();
    o.gravity = 0;
    // -1000: a floor, 0.02 · 1000² = 2·10⁴ over stop_stiffness (a heavy subtree's stop).
    (omega < 0 ? o.stop_frequency_floor : o.stop_frequency_limit) = std::abs(omega);
    auto b = build(text, o);
    REQUIRE(b->sim);
    // 0.02 · 300² = 1800 N·m/rad < 10⁴; 0.02 · 1000² = 2·10⁴ leaves stop_stiffness as a limit.
    const double k = omega == 300 ? 1800 : omega < 0 ? 2e4 : o.stop_stiffness;
    CAPTURE(omega);
    b->sim->set_joint_position(1, limit);
    b->sim->set_servo(1, {0, 2 * std::sqrt(k * 0.02) + 5, nullptr, nullptr, torque});
    b->sim->advance_to(2.0);
    CHECK(b->sim->joint_position(1) - limit == doctest::Approx(torque / k).epsilon(1e-4));
  }
}
