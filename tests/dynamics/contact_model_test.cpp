// The floor contact model (simulation.h ContactParams, the default points model) on one box,
// against what its documented law predicts, worked out here: the resting depth from the
// stiffness, the floor carrying the weight, Coulomb sliding at μ·g, the slide down a slope
// steeper than atan μ, and the creep speed of the regularised friction on a gentler one.
#include <doctest/doctest.h>

#include <bodyfmt/dynamics/simulation.h>
#include <bodyfmt/load.h>

#include <cmath>

using namespace bodyfmt;
using namespace bodyfmt::dynamics;

namespace {

// A 2 kg box 0.4 x 0.3 x 0.2 m, its inertia m/12·(b² + c²), ...
const char* kBox = R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
links:
  - name: BOX
    joint_type: free
    mass: 2.0
    inertia: [0.0216667, 0, 0, 0, 0.0333333, 0, 0, 0, 0.0416667]
    elements:
      - type: Shape
        geometry: { type: Box, size: [0.4, 0.3, 0.2] }
)";

constexpr double kMass = 2, kG = 9.80665, kHalfHeight = 0.1;

struct Built {
  Model model;
  Derived derived;
  std::unique_ptr<Simulation> sim;
  CollectingSink sink;
};

/// The box standing on the floor at rest after 0.5 s.
std::unique_ptr<Built> settled_box(const SimOptions& options) {
  auto b = std::make_unique<Built>();
  std::optional<Model> model = load_body_string(kBox, "box.body", LoadOptions{}, b->sink);
  REQUIRE(model);
  b->model = std::move(*model);
  b->derived = compute_derived(b->model, b->sink);
  b->sim = Simulation::build(b->model, b->derived, options, b->sink);
  REQUIRE(b->sim);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().z() = kHalfHeight;
  b->sim->set_root_pose(X);
  b->sim->advance_to(0.5);
  return b;
}

double velocity_x(const Simulation& sim) { return sim.link_velocity(0).second.x(); }

/// ΣN averaged over 0.5 s in 1 ms samples (the stiff contact rings at a fraction of a percent).
double mean_floor_force(Simulation& sim) {
  const double t0 = sim.time();
  double sum = 0;
  for (int i = 1; i <= 500; ++i) {
    sim.advance_to(t0 + 0.001 * i);
    sum += sim.total_contact_force().z();
  }
  return sum / 500;
}

}  // namespace

TEST_CASE("contact model: a box rests on its four bottom corners, sunk by its weight over 4·k") {
  SUBCASE("stiffness chosen from the model: the weight on four points sinks reference_depth") {
    SimOptions options;
    auto b = settled_box(options);
    CHECK(b->sim->contact_points().size() == 8);  // the box's corners
    for (const ContactPoint& p : b->sim->contact_points())
      CHECK((p.position_in_link.cwiseAbs() - Eigen::Vector3d(0.2, 0.15, 0.1)).norm() < 1e-12);
    CHECK(b->sim->contact_stiffness() == doctest::Approx(kMass * kG / (4 * 1e-4)).epsilon(1e-12));
    b->sim->advance_to(1.5);
    CHECK(b->sim->max_penetration() == doctest::Approx(1e-4).epsilon(1e-3));
    CHECK(b->sim->link_pose(0).translation().z() == doctest::Approx(kHalfHeight - 1e-4).epsilon(1e-5));
    CHECK(mean_floor_force(*b->sim) == doctest::Approx(kMass * kG).epsilon(1e-4));
  }
  SUBCASE("a stiffness given: δ = m·g / (4·k)") {
    SimOptions options;
    options.contact_params.stiffness = 2e5;
    auto b = settled_box(options);
    b->sim->advance_to(1.5);
    CHECK(b->sim->max_penetration() == doctest::Approx(kMass * kG / (4 * 2e5)).epsilon(1e-3));
    CHECK(mean_floor_force(*b->sim) == doctest::Approx(kMass * kG).epsilon(1e-4));
  }
}

TEST_CASE("contact model: a box pushed at 1 m/s slides at −μ·g and stops after v²/(2·μ·g)") {
  SimOptions options;
  auto b = settled_box(options);
  const double mu = options.contact_params.friction, x0 = b->sim->link_pose(0).translation().x();
  b->sim->set_root_velocity(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0));
  b->sim->restart();
  const double t0 = b->sim->time();
  b->sim->advance_to(t0 + 0.1);
  CHECK(velocity_x(*b->sim) == doctest::Approx(1 - mu * kG * 0.1).epsilon(5e-3));
  b->sim->advance_to(t0 + 0.5);  // Coulomb stops it at 1/(μ·g) = 0.204 s
  CHECK(std::abs(velocity_x(*b->sim)) < 1e-3);
  // The last 5 cm/s decelerate more gently (the transition): at most 0.5 % farther.
  const double distance = b->sim->link_pose(0).translation().x() - x0;
  CHECK(distance >= 1 / (2 * mu * kG) * 0.999);
  CHECK(distance <= 1 / (2 * mu * kG) * 1.005);
}

TEST_CASE("contact model: on a slope steeper than atan μ the box slides at g·(sin θ − μ·cos θ)") {
  SimOptions options;
  const double theta = 35 * M_PI / 180, mu = options.contact_params.friction;
  options.gravity_direction = Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta));
  auto b = settled_box(options);  // sliding already: measure the speed gained in 0.5 s
  const double v0 = velocity_x(*b->sim);
  b->sim->advance_to(1.0);
  CHECK((velocity_x(*b->sim) - v0) / 0.5 ==
        doctest::Approx(kG * (std::sin(theta) - mu * std::cos(theta))).epsilon(1e-2));
}

TEST_CASE("contact model: on a gentler slope the box creeps at the speed where μ·x·(2 − x) = tan θ") {
  // Below the transition speed vt friction is μ·x·(2 − x) with x = |slip|/vt, so the box holds
  // on a slope only by creeping: x = 1 − √(1 − tan θ/μ); for 10° and μ = 0.5, 0.1954·vt.
  SimOptions options;
  const double theta = 10 * M_PI / 180, mu = options.contact_params.friction;
  const double vt = options.contact_params.transition_velocity;
  options.gravity_direction = Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta));
  auto b = settled_box(options);
  b->sim->advance_to(2.0);
  CHECK(velocity_x(*b->sim) == doctest::Approx(vt * (1 - std::sqrt(1 - std::tan(theta) / mu))).epsilon(1e-2));
}

namespace {

// A solid 2 kg cylinder, r = 0.1 m, h = 0.3 m, along its link's Y (Choreonoid's cylinder axis):
// lying on its side with the link unturned. Inertia m·(3r² + h²)/12 across, m·r²/2 along.
const char* kCylinder = R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
links:
  - name: ROLLER
    joint_type: free
    mass: 2.0
    inertia: [0.02, 0, 0, 0, 0.01, 0, 0, 0, 0.02]
    elements:
      - type: Shape
        geometry: { type: Cylinder, radius: 0.1, height: 0.3 }
)";

constexpr double kRadius = 0.1, kLength = 0.3;

std::unique_ptr<Built> cylinder_at(const Eigen::Isometry3d& X) {
  auto b = std::make_unique<Built>();
  std::optional<Model> model = load_body_string(kCylinder, "cylinder.body", LoadOptions{}, b->sink);
  REQUIRE(model);
  b->model = std::move(*model);
  b->derived = compute_derived(b->model, b->sink);
  b->sim = Simulation::build(b->model, b->derived, SimOptions{}, b->sink);
  REQUIRE(b->sim);
  b->sim->set_root_pose(X);
  return b;
}

}  // namespace

TEST_CASE("contact model: a cylinder on its side touches along its lowest line, whatever its roll") {
  // The floor carries it on the lowest points of its two end rims: 2 points sunk by m·g/(2·k),
  // k = m·g/(4·1e-4), at any roll angle. Rolled by half a facet of a 20-gon (9°), a tessellated
  // rim would rest on a flat 1.2 mm lower, and hold there.
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 20, Eigen::Vector3d::UnitY()).toRotationMatrix();
  X.translation().z() = kRadius;
  auto b = cylinder_at(X);
  b->sim->advance_to(1.0);
  CHECK(b->sim->link_pose(0).translation().z() == doctest::Approx(kRadius - 2e-4).epsilon(1e-4));
  CHECK(mean_floor_force(*b->sim) == doctest::Approx(kMass * kG).epsilon(1e-4));
}

TEST_CASE("contact model: a cylinder set rolling on its side rolls on at v = ω·r, without losing speed") {
  // Rolling without slip, the touching line does not move: no friction and no damping work,
  // so 1 m/s is kept for the whole second (a 20-gon would knock on every facet, 32 per second).
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().z() = kRadius - 2e-4;
  auto b = cylinder_at(X);
  b->sim->set_root_velocity(Eigen::Vector3d(0, 1 / kRadius, 0), Eigen::Vector3d(1, 0, 0));
  b->sim->advance_to(1.0);
  const auto [omega, v] = b->sim->link_velocity(0);
  CHECK(v.x() == doctest::Approx(1).epsilon(1e-3));
  CHECK(omega.y() == doctest::Approx(1 / kRadius).epsilon(1e-3));
  CHECK(b->sim->link_pose(0).translation().x() == doctest::Approx(1).epsilon(2e-3));
  CHECK(std::abs(b->sim->link_pose(0).translation().z() - (kRadius - 2e-4)) < 2e-5);
}

TEST_CASE("contact model: a cylinder standing on an end rests on its whole rim, level and still") {
  // Standing, the rim has no lowest point: its 20 points share the weight, 20 springs sunk by
  // m·g/(20·k), and it stays upright without drifting or turning.
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X.translation().z() = kLength / 2;
  auto b = cylinder_at(X);
  b->sim->advance_to(1.0);
  const Eigen::Isometry3d rest = b->sim->link_pose(0);
  CHECK(rest.translation().z() == doctest::Approx(kLength / 2 - 4e-4 / 20).epsilon(1e-5));
  CHECK(rest.translation().head<2>().norm() < 1e-9);
  CHECK(Eigen::AngleAxisd(rest.linear() * X.linear().transpose()).angle() < 1e-9);
  CHECK(mean_floor_force(*b->sim) == doctest::Approx(kMass * kG).epsilon(1e-4));
}
