// Generic physics checks for any model, fixed roots included (dynamics-checker.md §4 "Generic
// checks"): G2 mass matrix, G3 free fall, G4 zero-g conservation, G5 drop and settle, G6 joint
// ranges, G7 gravity load, G8 surface velocity, G9 determinism and convergence. G1 (inertia)
// is the validator's, which bodysim runs first. Each phase is a function; one that cannot apply
// says why in a SKIP line.

#include <bodyfmt/angles.h>
#include <bodyfmt/dynamics/checks.h>
#include <bodyfmt/physical.h>

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace bodyfmt::dynamics {
namespace {

constexpr double kDeg = kPi / 180;
constexpr double kStopFrequency = kGenericStopFrequency;  // rad/s: no stop rings faster (a 21 ms period)

CheckResult make(std::string name, double measured, double expected, std::string unit, std::string tolerance,
                 bool passed) {
  return {std::move(name), measured, expected, std::move(unit), std::move(tolerance), passed};
}

bool is_free_root(const Model& model) { return model.root().joint_type == JointType::kFree; }

/// True when a joint on the path to the root lets the link move (the physical gate's is_moving,
/// whose LinkPhysics::welded_to_world is the opposite): a link fixed to a fixed root, or carried
/// by a track, is part of the world.
bool moves_relative_to_world(const Model& model, LinkIndex link) {
  for (LinkIndex i = link; i >= 0; i = model.links[static_cast<std::size_t>(i)].parent)
    if (is_moving(model.links[static_cast<std::size_t>(i)])) return true;
  return false;
}

bool limited(double value) { return std::isfinite(value) && std::abs(value) < kUnlimited; }

bool in_subtree(const Model& model, LinkIndex link, LinkIndex top) {
  for (LinkIndex k = link; k >= 0; k = model.links[k].parent)
    if (k == top) return true;
  return false;
}

/// What every phase shares.
struct Generic {
  const Model& model;
  const Derived& derived;
  const SimOptions& options;
  std::vector<CheckResult>& results;
  CollectingSink quiet;
  void add(CheckResult r) { results.push_back(std::move(r)); }
  void skip(std::string name, std::string reason) {
    results.push_back(skipped_check(std::move(name), std::move(reason)));
  }
  std::unique_ptr<Simulation> build(const SimOptions& o) { return Simulation::build(model, derived, o, quiet); }
};

/// Servo gains that hold each joint against its subtree's weight with a sag of about 0.01 rad
/// (or 1 mm), damped near critically: P from the largest gravity load the subtree can put on
/// the joint, D = 2·√(P·I) from its inertia about the axis.
struct HoldGains {
  std::vector<double> p, d;
};
HoldGains hold_gains(const Model& model, const Derived& derived, const std::vector<double>& q, double gravity) {
  HoldGains gains{std::vector<double>(model.links.size(), 0.0), std::vector<double>(model.links.size(), 0.0)};
  const std::vector<Eigen::Isometry3d> X = compute_world_frames(model, q);
  for (std::size_t j = 0; j < model.links.size(); ++j) {
    const Link& link = model.links[j];
    if (!is_one_dof(link) || j == 0) continue;
    const bool revolute = link.joint_type == JointType::kRevolute;
    const Eigen::Vector3d a = (X[j].linear() * link.joint_axis.normalized()).normalized();
    double load = 0, mass = 0;
    for (std::size_t k = 0; k < model.links.size(); ++k) {
      if (!in_subtree(model, static_cast<LinkIndex>(k), static_cast<LinkIndex>(j))) continue;
      const Eigen::Vector3d r = X[k] * derived.mass[k].center_of_mass - X[j].translation();
      load += derived.mass[k].mass * gravity * (r - a * a.dot(r)).norm();
      mass += derived.mass[k].mass;
    }
    if (!revolute) load = mass * gravity;
    const double sag = revolute ? 0.01 : 0.001;
    gains.p[j] = std::max(load, mass * gravity * 0.05 + 1e-3) / sag;
    const double inertia = std::max(subtree_axis_inertia(model, derived, static_cast<LinkIndex>(j), q), 1e-9);
    gains.d[j] = 2 * std::sqrt(gains.p[j] * inertia);
  }
  return gains;
}

void mass_matrix(Generic& g, Simulation& sim) {
  const Model& model = g.model;
  std::vector<CheckResult>& results = g.results;
  // G2: the mass matrix is symmetric and positive definite at random poses inside the ranges.
  {
    std::mt19937 random(12);  // fixed seed: the same poses every run
    double worst_asymmetry = 0, worst_ratio = std::numeric_limits<double>::infinity(), worst_condition = 0;
    bool cholesky = true;
    const int poses = 20;
    int size = 0;
    for (int pose = 0; pose < poses; ++pose) {
      std::vector<double> q(model.links.size(), 0.0);
      for (std::size_t i = 0; i < model.links.size(); ++i) {
        const Link& link = model.links[i];
        if (!sim.has_joint(static_cast<LinkIndex>(i))) continue;
        const double span = link.joint_type == JointType::kRevolute ? kPi : 1.0;
        const double lo = std::max(link.joint_range_lower, -span), hi = std::min(link.joint_range_upper, span);
        q[i] = lo <= hi ? std::uniform_real_distribution<double>(lo, hi)(random) : 0.0;
      }
      const Eigen::MatrixXd M = sim.mass_matrix_at(q);
      size = static_cast<int>(M.rows());
      if (M.size() == 0) break;
      const double scale = M.cwiseAbs().maxCoeff();
      worst_asymmetry = std::max(worst_asymmetry, (M - M.transpose()).cwiseAbs().maxCoeff() / scale);
      cholesky = cholesky && Eigen::LLT<Eigen::MatrixXd>(M).info() == Eigen::Success;
      const Eigen::VectorXd eigen = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
      worst_ratio = std::min(worst_ratio, eigen.minCoeff() / eigen.maxCoeff());
      worst_condition = std::max(worst_condition, eigen.maxCoeff() / eigen.minCoeff());
    }
    if (size > 0) {
      results.push_back(make(fmt::format("mass matrix ({0}×{0}) symmetric at {1} random poses", size, poses),
                             worst_asymmetry, 0, "rel", "≤ 1e-12", worst_asymmetry <= 1e-12));
      results.push_back(
          make(fmt::format("mass matrix positive definite (Cholesky; worst condition number {:.3g})", worst_condition),
               worst_ratio, 0, "λmin/λmax", "> 0", cholesky && worst_ratio > 0));
    }
  }

  if (results.empty() || results.back().name.rfind("mass matrix", 0) != 0)
    g.skip("G2 mass matrix", "the model has no degree of freedom");
}

/// G3: no floor, gravity on: the centre of mass falls at g, joints at rest stay at rest, and
/// the central angular momentum stays 0.
void free_fall(Generic& g) {
  const std::string name = "G3 free fall";
  if (!is_free_root(g.model)) {
    g.skip(name, "the root is fixed to the world, so the model cannot fall");
    return;
  }
  SimOptions o = g.options;
  o.contact = false;
  o.joint_stops = false;
  o.accuracy = 1e-10;
  std::unique_ptr<Simulation> sim = g.build(o);
  if (!sim) return;
  const Eigen::Vector3d c0 = sim->center_of_mass();
  std::vector<double> q0(g.model.links.size(), 0.0);
  for (std::size_t i = 0; i < g.model.links.size(); ++i)
    if (sim->has_joint(static_cast<LinkIndex>(i))) q0[i] = sim->joint_position(static_cast<LinkIndex>(i));
  const double t = 1.0;
  sim->advance_to(t);
  const Eigen::Vector3d a = 2 * (sim->center_of_mass() - c0) / (t * t);
  g.add(make(name + ": the centre of mass falls at g (relative error of its acceleration)",
             (a - Eigen::Vector3d(0, 0, -o.gravity)).norm() / o.gravity, 0, "", "≤ 1e-9",
             (a - Eigen::Vector3d(0, 0, -o.gravity)).norm() <= 1e-9 * o.gravity));
  double moved = 0;
  for (std::size_t i = 0; i < g.model.links.size(); ++i)
    if (sim->has_joint(static_cast<LinkIndex>(i)))
      moved = std::max(moved, std::abs(sim->joint_position(static_cast<LinkIndex>(i)) - q0[i]));
  g.add(make(name + ": joints at rest stay at rest (largest joint motion over 1 s)", moved, 0, "", "≤ 1e-9",
             moved <= 1e-9));
  const double h = sim->central_momentum().first.norm();
  g.add(make(name + ": angular momentum about the centre of mass stays 0", h, 0, "kg·m²/s", "≤ 1e-9", h <= 1e-9));
}

/// G4: no gravity, contact, stops or servos, random velocities: energy (and, with a free root,
/// momentum) conserved over 2 s at accuracy 1e-8.
void conservation(Generic& g) {
  SimOptions o = g.options;
  o.gravity = 0;
  o.contact = false;
  o.joint_stops = false;
  o.accuracy = 1e-8;
  std::unique_ptr<Simulation> sim = g.build(o);
  if (!sim) return;
  std::mt19937 random(4);
  std::uniform_real_distribution<double> u(-1, 1);
  const bool free = is_free_root(g.model);
  if (free)
    sim->set_root_velocity(Eigen::Vector3d(u(random), u(random), u(random)) * 0.5,
                           Eigen::Vector3d(u(random), u(random), u(random)) * 0.3);
  bool any = free;
  for (std::size_t i = 0; i < g.model.links.size(); ++i)
    if (sim->has_joint(static_cast<LinkIndex>(i))) {
      sim->set_joint_velocity(static_cast<LinkIndex>(i), u(random));
      any = true;
    }
  if (!any) {
    g.skip("G4 no gravity: conservation", "nothing moves: a fixed root and no joint");
    return;
  }
  const double e0 = sim->energy();
  const auto [h0, p0] = sim->central_momentum();
  // The momenta are judged relative to the largest the model's kinetic energy could carry, not
  // to what the random velocities happened to give: |H| ≤ √(2·E·I_max) about the centre of
  // mass and |p| ≤ √(2·E·m). Relative to a small |H0| (random velocities that nearly cancel
  // about the centre of mass) the integration error of a gram-scale model read as 1e-6 while its
  // energy drifted 1e-10.
  const Eigen::Vector3d c = sim->center_of_mass();
  Eigen::Matrix3d central = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < g.model.links.size(); ++k) {
    const Eigen::Isometry3d X = sim->link_pose(static_cast<LinkIndex>(k));
    const double m = g.derived.mass[k].mass;
    const Eigen::Vector3d r = X * g.derived.mass[k].center_of_mass - c;
    central += X.linear() * sim->link_inertias()[k] * X.linear().transpose() +
               m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  const double largest_inertia = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(central).eigenvalues().maxCoeff();
  const double h_scale = std::max({h0.norm(), std::sqrt(2 * e0 * largest_inertia), 1e-300});
  const double p_scale = std::max({p0.norm(), std::sqrt(2 * e0 * g.derived.total_mass), 1e-300});
  double worst_e = 0, worst_h = 0, worst_p = 0;
  for (int i = 1; i <= 20; ++i) {
    sim->advance_to(0.1 * i);
    worst_e = std::max(worst_e, std::abs(sim->energy() - e0) / e0);
    const auto [h, p] = sim->central_momentum();
    worst_h = std::max(worst_h, (h - h0).norm() / h_scale);
    worst_p = std::max(worst_p, (p - p0).norm() / p_scale);
  }
  g.add(make("G4 no gravity, 2 s: energy drift, relative to the initial energy", worst_e, 1e-6, "", "≤ 1e-6",
             worst_e <= 1e-6));
  if (!free) {
    g.skip("G4 no gravity: momentum", "the root is fixed to the world, which exerts forces on the model");
    return;
  }
  g.add(
      make("G4 no gravity, 2 s: angular momentum drift about the centre of mass, relative to √(2 × energy × "
           "largest central inertia)",
           worst_h, 1e-6, "", "≤ 1e-6", worst_h <= 1e-6));
  g.add(make("G4 no gravity, 2 s: linear momentum drift, relative to √(2 × energy × mass)", worst_p, 1e-6, "", "≤ 1e-6",
             worst_p <= 1e-6));
}

/// G5: drop from 2 cm onto the floor (free roots).
void drop(Generic& g, const std::vector<ContactPoint>& contacts) {
  if (!is_free_root(g.model)) {
    g.skip("G5 drop and settle", "the root is fixed to the world, so there is nothing to drop");
    return;
  }
  if (contacts.empty()) {
    g.skip("G5 drop and settle", "the model has no collision geometry to land on");
    return;
  }
  const Model& model = g.model;
  const Derived& derived = g.derived;
  const SimOptions& options = g.options;
  std::vector<CheckResult>& results = g.results;
  std::unique_ptr<Simulation> sim;
  for (const bool locked : {false, true}) {
    SimOptions drop_options = options;
    drop_options.lock_joints = locked;
    sim = g.build(drop_options);
    if (!sim) break;
    double lowest = std::numeric_limits<double>::infinity();
    BoundingBox box;
    // The built system's pose: the file's, with the joints at their initial displacements
    // (derived.X_WL has them at zero, which would drop a bent model from the wrong height).
    for (const ContactPoint& p : sim->contact_points()) {
      const Eigen::Isometry3d X = sim->link_pose(p.link);
      lowest = std::min(lowest, p.touching(X).z());
      box.add(p.touching(X));
      box.add(p.top(X));
    }
    const double drop = 0.02;
    Eigen::Isometry3d X = as_isometry(model.root().X_PL);
    X.translation().z() += drop - lowest;
    sim->set_root_pose(X);
    const double mass = derived.total_mass;
    const double height = std::max(box.max.z() - box.min.z(), 1e-3);
    const double e0 = sim->energy();
    double gain = 0;
    bool finite = true;
    const Eigen::Vector3d start = sim->link_pose(0).translation();
    // How far the root can travel by turning about a contact point that does not slip: the
    // largest distance from the root origin to a contact point, times the angle turned.
    double reach = 0;
    for (const ContactPoint& p : sim->contact_points())
      reach = std::max(reach, (sim->link_pose(p.link) * p.position_in_link - start).norm() + p.radius);
    double turned = 0;  // ∫|ω| dt of the root, summed over the samples
    Eigen::Matrix3d last_rotation = sim->link_pose(0).linear();
    const double duration = 3.0;
    const double settle = 1e-4 * mass * options.gravity * height;
    // The free drop ends once the model has rested for kRest (kinetic energy under the settle
    // bound of the locked drop), at the latest at `duration`. A passive model gains energy only
    // through a force doing work on something that moves, and an unstable mode (a stop or
    // contact that pumps energy) grows out of rest into motion above the bound within that time.
    const double kRest = 0.5;
    double rest_start = -1, end = duration;
    std::string failure;
    try {
      for (int i = 1; i <= static_cast<int>(duration / 0.005); ++i) {
        sim->advance_to(0.005 * i);
        if (!sim->finite()) {
          finite = false;
          break;
        }
        gain = std::max(gain, sim->energy() - e0);
        const Eigen::Matrix3d rotation = sim->link_pose(0).linear();
        turned += Eigen::AngleAxisd(rotation * last_rotation.transpose()).angle();
        last_rotation = rotation;
        if (locked) continue;
        if (sim->kinetic_energy() > settle) {
          rest_start = -1;
        } else if (rest_start < 0) {
          rest_start = sim->time();
        } else if (sim->time() - rest_start >= kRest - 1e-9) {
          end = sim->time();
          break;
        }
      }
    } catch (const WorkBudgetExceeded&) {
      throw;  // not a check that failed: the run stops, located at the cause
    } catch (const std::exception& e) {
      finite = false;
      failure = e.what();
    }
    const std::string label = locked ? "G5 drop 2 cm, joints locked" : "G5 drop 2 cm, joints free";
    results.push_back(verdict_check(
        label + ": state stays finite", finite,
        finite ? "every position and velocity stayed finite"
               : "the state became NaN or infinite" + (failure.empty() ? std::string() : " (" + failure + ")")));
    if (!finite) continue;
    // Energy never grows while passive, beyond integration error: 1e-4 of the drop energy.
    // After release it only decreases, whatever face the model lands on and however it tumbles.
    const double drop_energy = mass * options.gravity * drop;
    if (!locked) {
      const std::string window = end < duration ? fmt::format("over {:.3g} s, at rest for the last {:g} s", end, kRest)
                                                : fmt::format("over {:g} s", duration);
      results.push_back(make(fmt::format("{}: largest energy gain {}", label, window), gain, 1e-4 * drop_energy, "J",
                             "≤ 1e-4 × drop energy", gain <= 1e-4 * drop_energy));
      continue;
    }
    results.push_back(make(fmt::format("{}: largest energy gain over {:g} s", label, duration), gain,
                           1e-4 * drop_energy, "J", "≤ 1e-4 × drop energy", gain <= 1e-4 * drop_energy));
    const double ke = sim->kinetic_energy();
    if (ke > settle) {
      // A model that lands on a round face, or tips and rocks, may still roll after 3 s: that
      // is physics, not a defect (its energy has only gone down, above). What holds at rest
      // cannot be judged on it.
      g.skip(fmt::format("{}: at rest after {:g} s", label, duration),
             fmt::format("it does not come to rest within {:g} s: kinetic energy {:.3g} J, above the rest bound "
                         "{:.3g} J (1e-4 × weight × height); it still rolls or rocks, so its penetration, floor "
                         "force and drift at rest are not judged",
                         duration, ke, settle));
      continue;
    }
    results.push_back(make(fmt::format("{}: kinetic energy at {:g} s", label, duration), ke, settle, "J",
                           "≤ 1e-4 × weight × height", ke <= settle));
    const double depth = sim->max_penetration();
    results.push_back(
        make(label + ": penetration at rest", depth * 1e3, 2, "mm", "(0, 2] mm", depth > 0 && depth <= 2e-3));
    const double fz = sim->total_contact_force().z();
    results.push_back(make(label + ": floor force at rest equals the weight", fz, mass * options.gravity, "N", "±1 %",
                           std::abs(fz - mass * options.gravity) <= 0.01 * mass * options.gravity));
    // A model that lands flat stays where it fell (1 cm of slip at the impact). One that tips,
    // rolls or tumbles moves its root by turning about its contacts: no further than the angle
    // it turned times the largest distance from the root to a contact point, plus that slip.
    const Eigen::Vector3d moved = sim->link_pose(0).translation() - start;
    const double drift = std::hypot(moved.x(), moved.y());
    const double allowed = 0.01 + turned * reach;
    results.push_back(make(fmt::format("{}: horizontal drift of the root (turned {:.3g} rad in all, {:.3g} m from "
                                       "the root to its farthest contact point)",
                                       label, turned, reach),
                           drift * 1e3, allowed * 1e3, "mm", "≤ 10 mm + turned × that distance", drift <= allowed));
  }
}

/// G6: every limited joint pushed past each limit at once (no gravity, no contact): the stops
/// hold within 1° (revolute) or 1 mm (prismatic).
void joint_ranges(Generic& g) {
  const Model& model = g.model;
  std::vector<LinkIndex> joints;
  std::string unlimited;
  for (std::size_t i = 1; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    if (!is_one_dof(link)) continue;
    if (limited(link.joint_range_lower) || limited(link.joint_range_upper))
      joints.push_back(static_cast<LinkIndex>(i));
    else
      unlimited += (unlimited.empty() ? "\"" : ", \"") + link.name + "\"";
  }
  if (!unlimited.empty()) g.skip("G6 joint ranges of " + unlimited, "unlimited ranges: no stop to test");
  if (joints.empty()) {
    if (unlimited.empty()) g.skip("G6 joint ranges", "the model has no revolute or prismatic joint");
    return;
  }
  if (!g.options.joint_stops) {
    g.skip("G6 joint ranges", "joint stops are off");
    return;
  }
  SimOptions o = g.options;
  o.gravity = 0;
  o.contact = false;
  // The stops pushed here are the ones every generic phase uses (no stiffer than I·(300 rad/s)²,
  // see run_generic_checks); a joint without a stop still ends about 5° (3 mm) past.
  // Revolute and prismatic joints are pushed in separate runs, the others held where they are:
  // revolute stops hitting at speed shake a light slider through its (softer, 1 mm) stop.
  for (int run = 0; run < 4; ++run) {
    const int side = run % 2;
    const JointType kind = run < 2 ? JointType::kRevolute : JointType::kPrismatic;
    const std::string label =
        fmt::format("G6 joint ranges: worst overshoot of a {} joint past its {} limit",
                    kind == JointType::kRevolute ? "revolute" : "prismatic", side == 0 ? "upper" : "lower");
    bool any = false;
    for (LinkIndex j : joints) any = any || model.links[j].joint_type == kind;
    if (!any) continue;
    std::unique_ptr<Simulation> sim = g.build(o);
    if (!sim) return;
    std::vector<std::pair<LinkIndex, double>> pushed;
    for (std::size_t i = 1; i < model.links.size(); ++i) {
      const Link& link = model.links[i];
      if (!sim->has_joint(static_cast<LinkIndex>(i))) continue;
      const bool revolute = link.joint_type == JointType::kRevolute;
      const double limit = side == 0 ? link.joint_range_upper : link.joint_range_lower;
      // Started 2° (2 mm) inside the limit and pushed toward 5° (3 mm) past it: slowly enough
      // that the stop is met nearly at rest, whatever the subtree's inertia; without the stop
      // the joint would end 5° (3 mm) past it.
      const double sign = side == 0 ? 1 : -1;
      const double beyond = sign * (revolute ? 5 * kDeg : 0.003);
      const double inside = sign * (revolute ? 2 * kDeg : 0.002);
      const bool push = limited(limit) && link.joint_type == kind;
      const double target = push ? limit + beyond : sim->joint_position(static_cast<LinkIndex>(i));
      if (push) {
        pushed.emplace_back(static_cast<LinkIndex>(i), limit);
        sim->set_joint_position(static_cast<LinkIndex>(i), limit - inside);
      }
      // Gains for a 6 rad/s, critically damped approach of each joint's subtree: a stiffer
      // servo spins light links so fast that the whole chain shakes.
      const double inertia = std::max(subtree_axis_inertia(model, g.derived, static_cast<LinkIndex>(i), {}), 1e-9);
      const double omega = 6;
      sim->set_servo(static_cast<LinkIndex>(i),
                     {omega * omega * inertia, 2 * omega * inertia, [target](double) { return target; }, nullptr, 0});
    }
    if (pushed.empty()) {
      g.skip(label, "no joint is limited on this side");
      continue;
    }
    // Sampled finely: the overshoot is a transient peak against the stop.
    std::vector<double> extreme(model.links.size(), side == 0 ? -1e300 : 1e300);
    for (int k = 1; k <= 160; ++k) {
      sim->advance_to(0.005 * k);
      for (const auto& [joint, limit] : pushed) {
        const double q = sim->joint_position(joint);
        extreme[joint] = side == 0 ? std::max(extreme[joint], q) : std::min(extreme[joint], q);
      }
    }
    double worst = -1e300;
    std::string where;
    for (const auto& [joint, limit] : pushed) {
      const bool revolute = model.links[joint].joint_type == JointType::kRevolute;
      const double over = (side == 0 ? extreme[joint] - limit : limit - extreme[joint]) / (revolute ? kDeg : 0.001);
      if (over > worst) {
        worst = over;
        where = fmt::format("\"{}\" at {:.4g} {}, limit {:.4g}", model.links[joint].name,
                            extreme[joint] / (revolute ? kDeg : 0.001), revolute ? "°" : "mm",
                            limit / (revolute ? kDeg : 0.001));
      }
    }
    const bool degrees = kind == JointType::kRevolute;
    g.add(make(fmt::format("{} ({} joints, stops between the subtree inertia × ({:g} rad/s)² and × ({:g} rad/s)²; {})",
                           label, pushed.size(), kGenericStopFloorFrequency, kStopFrequency, where),
               worst, 1, degrees ? "°" : "mm", degrees ? "≤ 1°" : "≤ 1 mm", worst <= 1));
  }
}

/// The joint positions where the hold servos balance gravity: q = q0 + τ_g(q)/P, by fixed-point
/// iteration from the model's own kinematics (reference.cpp), independent of Simbody.
std::vector<double> gravity_equilibrium(const Model& model, const Derived& derived, const HoldGains& gains,
                                        const std::vector<double>& q0, double gravity, bool& converged) {
  std::vector<double> q = q0;
  converged = false;
  for (int iteration = 0; iteration < 200 && !converged; ++iteration) {
    double change = 0;
    std::vector<double> next = q;
    for (std::size_t j = 1; j < model.links.size(); ++j) {
      if (gains.p[j] <= 0) continue;
      next[j] = q0[j] + subtree_gravity_torque(model, derived, static_cast<LinkIndex>(j), q, gravity) / gains.p[j];
      change = std::max(change, std::abs(next[j] - q[j]));
    }
    q = next;
    converged = change < 1e-13;
  }
  return q;
}

/// The pose G7 and G9 hold: each joint turned 0.5 rad (alternately up and down) or slid to the
/// middle of its range, inside the range, so that gravity loads the joints (a model at its file
/// pose often stands straight up, where it loads none).
std::vector<double> hold_pose(const Model& model) {
  std::vector<double> q(model.links.size(), 0.0);
  double sign = 1;
  for (std::size_t j = 1; j < model.links.size(); ++j) {
    const Link& link = model.links[j];
    if (!is_one_dof(link)) continue;
    const double lo = limited(link.joint_range_lower) ? link.joint_range_lower : -1e9;
    const double hi = limited(link.joint_range_upper) ? link.joint_range_upper : 1e9;
    const double wanted = link.joint_type == JointType::kRevolute
                              ? sign * 0.5
                              : (limited(lo) && limited(hi) ? 0.5 * (lo + hi) : sign * 0.02);
    q[j] = lo <= hi ? std::clamp(wanted, lo + 0.1 * std::min(hi - lo, 1.0), hi - 0.1 * std::min(hi - lo, 1.0)) : 0.0;
    sign = -sign;
  }
  return q;
}

/// G7: with a fixed root and every joint PD-held at the hold pose, each joint sags to
/// where the servo balances the gravity load computed from the model (reference.cpp).
void gravity_load(Generic& g) {
  const std::string name = "G7 gravity load on the held joints";
  if (is_free_root(g.model)) {
    g.skip(name, "a free root falls over; this check holds the joints of a model whose root is fixed");
    return;
  }
  SimOptions o = g.options;
  o.contact = false;
  o.joint_stops = false;
  std::unique_ptr<Simulation> sim = g.build(o);
  if (!sim) return;
  const std::vector<double> q0 = hold_pose(g.model);
  const HoldGains gains = hold_gains(g.model, g.derived, q0, o.gravity);
  bool any = false;
  for (std::size_t j = 1; j < g.model.links.size(); ++j) {
    if (!sim->has_joint(static_cast<LinkIndex>(j))) continue;
    any = true;
    sim->set_joint_position(static_cast<LinkIndex>(j), q0[j]);
    const double target = q0[j];
    sim->set_servo(static_cast<LinkIndex>(j),
                   {gains.p[j], gains.d[j], [target](double) { return target; }, nullptr, 0});
  }
  if (!any) {
    g.skip(name, "the model has no revolute or prismatic joint");
    return;
  }
  bool converged = false;
  const std::vector<double> expected = gravity_equilibrium(g.model, g.derived, gains, q0, o.gravity, converged);
  if (!converged) {
    g.skip(name, "the equilibrium of the held joints did not converge (the servos are too weak for the load)");
    return;
  }
  sim->advance_to(2.0);
  const double ke = sim->kinetic_energy();
  double worst = 0, worst_sag = 0;
  std::string where = "every joint";
  for (std::size_t j = 1; j < g.model.links.size(); ++j) {
    if (!sim->has_joint(static_cast<LinkIndex>(j))) continue;
    const double sag = expected[j] - q0[j];
    const double error = std::abs(sim->joint_position(static_cast<LinkIndex>(j)) - expected[j]);
    const double relative = error / (0.01 * std::abs(sag) + 1e-7);
    if (relative > worst) {
      worst = relative;
      worst_sag = sag;
      where = fmt::format("\"{}\": sag {:.4g}, reference {:.4g}", g.model.links[j].name,
                          sim->joint_position(static_cast<LinkIndex>(j)) - q0[j], sag);
    }
  }
  (void)worst_sag;
  g.add(make(fmt::format("{}: kinetic energy after 2 s", name), ke, 1e-6, "J", "≤ 1e-6 J", ke <= 1e-6));
  g.add(make(
      fmt::format("{}: worst sag error against gravity torque / servo gain, in units of 1 % + 1e-7 ({})", name, where),
      worst, 1, "", "≤ 1", worst <= 1));
}

/// G8: each pseudo track's surface velocity: a box placed on a fixed conveyor's belt with
/// dq = +0.5 moves at dq·(a_w × n_out) (spec §1.4). bodysim has only floor contact, so it runs
/// the same contact by relativity: the model turned over onto its belt, free on the floor; the
/// box would move relative to the belt at minus the model's velocity.
void surface_velocity(Generic& g, const std::vector<ContactPoint>& contacts) {
  const Model& model = g.model;
  std::vector<LinkIndex> tracks;
  for (std::size_t i = 0; i < model.links.size(); ++i)
    if (model.links[i].joint_type == JointType::kPseudoContinuousTrack) tracks.push_back(static_cast<LinkIndex>(i));
  if (tracks.empty()) {
    g.skip("G8 surface velocity", "the model has no pseudo_continuous_track link");
    return;
  }
  if (is_free_root(model)) {
    g.skip("G8 surface velocity", "a vehicle's tracks are driven against the floor by bodysim check-tank");
    return;
  }
  const std::vector<Eigen::Isometry3d> X = compute_world_frames(model);
  const double dq = 0.5;
  for (LinkIndex track : tracks) {
    const std::string label =
        fmt::format("G8 surface velocity of \"{}\" at dq = {:+g}: a box on its top", model.links[track].name, dq);
    double top = -std::numeric_limits<double>::infinity(), others = -std::numeric_limits<double>::infinity();
    LinkIndex highest = -1;
    for (const ContactPoint& p : contacts) {
      const double z = p.top(X[p.link]).z();
      if (p.link == track)
        top = std::max(top, z);
      else if (z > others) {
        others = z;
        highest = p.link;
      }
    }
    if (!std::isfinite(top)) {
      g.skip(label, "the track has no collision geometry");
      continue;
    }
    if (others > top - 1e-6) {
      g.skip(label, fmt::format("link \"{}\" reaches {:.4g} m above the belt's top: a box would rest on it",
                                model.links[highest].name, others - top));
      continue;
    }
    const Eigen::Vector3d a = (X[track].linear() * model.links[track].joint_axis.normalized()).normalized();
    const Eigen::Vector3d expected = dq * a.cross(Eigen::Vector3d::UnitZ()).normalized();
    if (!(a.cross(Eigen::Vector3d::UnitZ()).norm() > 1e-9)) {
      g.skip(label, "the track's axis is vertical: its top surface does not move");
      continue;
    }
    Model turned = model;
    turned.links[0].joint_type = JointType::kFree;
    SimOptions o = g.options;
    o.lock_joints = true;
    std::unique_ptr<Simulation> sim = Simulation::build(turned, g.derived, o, g.quiet);
    if (!sim) return;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    Eigen::Isometry3d X_root = Eigen::Isometry3d::Identity();
    X_root.linear() = R * X[0].linear();
    X_root.translation() = R * X[0].translation() + Eigen::Vector3d(0, 0, top);
    sim->set_root_pose(X_root);
    sim->advance_to(0.3);
    sim->set_track_speed(track, dq);
    sim->advance_to(2.3);
    const Eigen::Vector3d v_model = sim->center_of_mass_velocity();
    const Eigen::Vector3d v_box = R.transpose() * -v_model;  // back in the upright conveyor's axes
    const Eigen::Vector3d d = expected.normalized();
    g.add(make(fmt::format("{} (axis {:.3g} {:.3g} {:.3g}), velocity along a × z", label, a.x(), a.y(), a.z()),
               v_box.dot(d), dq, "m/s", "±1 %", std::abs(v_box.dot(d) - dq) <= 0.01 * dq));
    g.add(make(label + ", velocity v_x", v_box.x(), expected.x(), "m/s", "±1 % of dq",
               std::abs(v_box.x() - expected.x()) <= 0.01 * dq));
  }
}

/// G9: the same run twice is bitwise identical; a tenfold tighter accuracy changes where the
/// links end up by < 1 % of how far they moved.
void determinism(Generic& g, const std::vector<ContactPoint>& contacts) {
  const HoldGains gains = hold_gains(g.model, g.derived, hold_pose(g.model), g.options.gravity);
  // A fixed root stays where the file puts it: a model hanging below z = 0 (a gripper at the
  // origin) would start with its moving links deep inside the floor, which then throws them out
  // with forces no step budget integrates. G9 tests the simulation, not that placement: it runs
  // without the floor then, and says so.
  std::string floor_note;
  if (!is_free_root(g.model) && g.options.contact) {
    const std::vector<Eigen::Isometry3d> X = compute_world_frames(g.model, hold_pose(g.model));
    double deepest = 0;
    for (const ContactPoint& p : contacts) {
      if (!moves_relative_to_world(g.model, p.link)) continue;
      const double z = p.touching(X[static_cast<std::size_t>(p.link)]).z();
      if (z < deepest) {
        deepest = z;
        floor_note = fmt::format(" (without the floor: the root is fixed, and link \"{}\" starts {:.3g} m inside it)",
                                 g.model.links[static_cast<std::size_t>(p.link)].name, -z);
      }
    }
  }
  auto run = [&](double accuracy) {
    SimOptions o = g.options;
    o.accuracy = accuracy;
    if (!floor_note.empty()) o.contact = false;
    std::vector<double> out;
    std::unique_ptr<Simulation> sim = g.build(o);
    if (!sim) return out;
    const std::vector<double> q0 = hold_pose(g.model);
    for (std::size_t j = 1; j < g.model.links.size(); ++j)
      if (sim->has_joint(static_cast<LinkIndex>(j))) {
        sim->set_joint_position(static_cast<LinkIndex>(j), q0[j]);
        const double target = q0[j];
        sim->set_servo(static_cast<LinkIndex>(j),
                       {gains.p[j], gains.d[j], [target](double) { return target; }, nullptr, 0});
      }
    if (is_free_root(g.model)) {
      // 2 cm above the floor in the held pose, not the zero pose.
      double lowest = std::numeric_limits<double>::infinity();
      for (const ContactPoint& p : contacts) lowest = std::min(lowest, p.touching(sim->link_pose(p.link)).z());
      Eigen::Isometry3d X = as_isometry(g.model.root().X_PL);
      if (std::isfinite(lowest)) X.translation().z() += 0.02 - lowest;
      sim->set_root_pose(X);
    }
    std::vector<Eigen::Vector3d> start;
    for (std::size_t k = 0; k < g.model.links.size(); ++k)
      start.push_back(sim->link_pose(static_cast<LinkIndex>(k)).translation());
    sim->advance_to(0.3);
    for (std::size_t k = 0; k < g.model.links.size(); ++k) {
      const Eigen::Vector3d x = sim->link_pose(static_cast<LinkIndex>(k)).translation();
      for (int c = 0; c < 3; ++c) out.push_back(x[c]);
      for (int c = 0; c < 3; ++c) out.push_back(x[c] - start[k][c]);
    }
    return out;
  };
  const std::vector<double> first = run(g.options.accuracy), second = run(g.options.accuracy);
  const std::vector<double> fine = run(g.options.accuracy / 10);
  if (first.empty() || second.empty() || fine.empty()) return;
  int differ = 0;
  for (std::size_t i = 0; i < first.size(); ++i) differ += first[i] == second[i] ? 0 : 1;
  const std::string name =
      "G9 determinism: link positions after 0.3 s held at a pose (a free root dropped 2 cm), two runs, values that "
      "differ" +
      floor_note;
  g.add(make(name, differ, 0, "", "= 0", differ == 0));
  double moved = 0, change = 0;
  for (std::size_t i = 0; i < first.size(); i += 6)
    for (int c = 0; c < 3; ++c) {
      moved = std::max(moved, std::abs(first[i + 3 + c]));
      change = std::max(change, std::abs(first[i + c] - fine[i + c]));
    }
  g.add(make(fmt::format("G9 convergence: accuracy {:g} against {:g}, largest change of a link position{}",
                         g.options.accuracy, g.options.accuracy / 10, floor_note),
             change, 0.01 * moved + 1e-6, "m", "≤ 1 % of the largest motion + 1 µm", change <= 0.01 * moved + 1e-6));
}

}  // namespace

std::vector<CheckResult> run_generic_checks(const Model& model, const Derived& derived, const SimOptions& options,
                                            DiagnosticSink& sink, std::string& why) {
  std::vector<CheckResult> results;
  std::unique_ptr<Simulation> sim = Simulation::build(model, derived, options, sink);
  if (!sim) {
    why = "the model cannot be simulated as written (see above)";
    return results;
  }
  // Every phase's joint stops are no stiffer than I·(300 rad/s)² about the joint's subtree. A
  // stop is the checker's choice (Choreonoid's AIST simulator does not enforce ranges at all),
  // and G6 proves the stops used here hold each range within 1° (1 mm). 10⁴ N·m/rad on a light
  // link (GR001's 5 g head, I = 6.7e-7 kg·m²) rings at 1.2e5 rad/s and held the explicit
  // integrator to 40 µs steps wherever a joint leant on its stop: all of G6's push, and G5's
  // free drop once the limbs collapse onto their stops.
  // No stop is softer than I·(30 rad/s)² either: G6's servo pushes a joint with I·(6 rad/s)²,
  // so that a heavy subtree (713 kg, I = 2.4e3 kg·m²) went 1.5° through a 10⁴ N·m/rad stop; at
  // I·30² it holds within 5° × 36/(36 + 900) = 0.2°, whatever the mass.
  SimOptions capped = options;
  capped.stop_frequency_limit = kStopFrequency;
  capped.stop_frequency_floor = kGenericStopFloorFrequency;
  Generic g{model, derived, capped, results, {}};
  const std::vector<ContactPoint> contacts = sim->contact_points();
  mass_matrix(g, *sim);
  sim.reset();
  free_fall(g);
  conservation(g);
  drop(g, contacts);
  joint_ranges(g);
  gravity_load(g);
  surface_velocity(g, contacts);
  determinism(g, contacts);
  return results;
}

}  // namespace bodyfmt::dynamics
