// The tank suite (dynamics-checker.md §4, issues 12 and 24): how the vehicle stands, settling,
// straight drive, spin in place, turret servos and joint stops, and conservation, on any model
// with two pseudo tracks. Each phase is a function that appends its lines; a check that cannot
// apply is a SKIP line with its reason.

#include <bodyfmt/angles.h>
#include <bodyfmt/dynamics/checks.h>
#include <bodyfmt/dynamics/servo_reference.h>
#include <bodyfmt/inertia.h>

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

namespace bodyfmt::dynamics {
namespace {

constexpr double kDeg = kPi / 180;

bool is_track(const Link& link) { return link.joint_type == JointType::kPseudoContinuousTrack; }

Eigen::Vector3d mean(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : points) sum += p;
  return points.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(points.size()));
}

double yaw_of(const Eigen::Isometry3d& X) {
  const Eigen::Vector3d x = X.linear().col(0);
  return std::atan2(x.y(), x.x());
}

double wrap(double angle) { return std::remainder(angle, 2 * kPi); }

CheckResult relative(std::string name, double measured, double expected, double tolerance, std::string unit) {
  CheckResult r{std::move(name), measured, expected, std::move(unit), fmt::format("±{:g} %", tolerance * 100), false};
  r.passed = std::isfinite(measured) && std::abs(measured - expected) <= tolerance * std::abs(expected);
  return r;
}
CheckResult absolute(std::string name, double measured, double expected, double tolerance, std::string unit) {
  CheckResult r{std::move(name), measured, expected, unit, fmt::format("±{:g} {}", tolerance, unit), false};
  r.passed = std::isfinite(measured) && std::abs(measured - expected) <= tolerance;
  return r;
}
CheckResult at_most(std::string name, double measured, double bound, std::string unit) {
  CheckResult r{std::move(name), measured, bound, std::move(unit), "≤ expected", false};
  r.passed = std::isfinite(measured) && measured <= bound;
  return r;
}
CheckResult at_least(std::string name, double measured, double bound, std::string unit) {
  CheckResult r{std::move(name), measured, bound, std::move(unit), "≥ expected", false};
  r.passed = std::isfinite(measured) && measured >= bound;
  return r;
}
CheckResult within(std::string name, double measured, double expected, double lo, double hi, std::string unit) {
  CheckResult r{std::move(name), measured, expected, unit, fmt::format("[{:g}, {:g}] {}", lo, hi, unit), false};
  r.passed = std::isfinite(measured) && measured >= lo && measured <= hi;
  return r;
}

/// Minimum-jerk profile from 0 to `distance` in `duration`: position, velocity.
double min_jerk(double t, double distance, double duration) {
  const double s = std::clamp(t / duration, 0.0, 1.0);
  return distance * (10 * std::pow(s, 3) - 15 * std::pow(s, 4) + 6 * std::pow(s, 5));
}
double min_jerk_rate(double t, double distance, double duration) {
  const double s = std::clamp(t / duration, 0.0, 1.0);
  return distance / duration * (30 * s * s - 60 * s * s * s + 30 * s * s * s * s);
}

/// Shared by every scenario: a fresh system standing on the floor, joint servos holding 0.
class Scenario {
 public:
  Scenario(const Model& model, const Derived& derived, const TankOpening& opening, const TankSuiteOptions& options,
           const SimOptions& sim_options, DiagnosticSink& sink)
      : tank_(opening.tank), options_(options) {
    sim_ = Simulation::build(model, derived, sim_options, sink);
    if (!sim_) return;
    sim_->set_root_pose(opening.start);
    // As a controller holds them: every joint, not only the turret's (a joint left free swings).
    for (LinkIndex joint : opening.held_joints) hold(joint, 0.0);
  }
  explicit operator bool() const { return sim_ != nullptr; }
  Simulation& sim() { return *sim_; }
  void hold(LinkIndex joint, double q) {
    servo(
        joint, [q](double) { return q; }, nullptr);
  }
  void servo(LinkIndex joint, std::function<double(double)> q_ref, std::function<double(double)> qd_ref) {
    sim_->set_servo(joint, {options_.p_gain, options_.d_gain, std::move(q_ref), std::move(qd_ref), 0});
  }
  /// Track commands as a controller sends them: dq of the left and right track, whatever
  /// their axes (Choreonoid's tank controllers send the same dq to both to go straight).
  void drive(double left, double right) {
    sim_->set_track_speed(tank_.left, left);
    sim_->set_track_speed(tank_.right, right);
  }
  /// Advances by `duration` in samples of `dt`, calling `sample` after each.
  template <class F>
  void run(double duration, F sample, double dt = 0.005) {
    const double start = sim_->time();
    const int n = static_cast<int>(std::lround(duration / dt));
    for (int i = 1; i <= n; ++i) {
      sim_->advance_to(start + i * dt);
      sample(sim_->time() - start);
    }
  }
  void run(double duration) {
    run(duration, [](double) {});
  }
  /// Root velocity split along the vehicle's current heading: forward, lateral, yaw rate.
  Eigen::Vector3d heading_velocity() const {
    const Eigen::Isometry3d X = sim_->link_pose(0);
    const auto [omega, v] = sim_->link_velocity(0);
    const Eigen::Vector3d f = X.linear().col(0);
    const Eigen::Vector3d l = X.linear().col(1);
    return {v.dot(f), v.dot(l), omega.z()};
  }

  /// Forward speed of the centre of mass along the vehicle's current heading.
  double com_forward_speed() const { return sim_->center_of_mass_velocity().dot(sim_->link_pose(0).linear().col(0)); }

 private:
  const TankLayout& tank_;
  const TankSuiteOptions& options_;
  std::unique_ptr<Simulation> sim_;
};

std::string vector_text(const Eigen::Vector3d& v) {
  auto clean = [](double x) { return std::abs(x) < 5e-10 ? 0.0 : x; };
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", clean(v.x()), clean(v.y()), clean(v.z()));
}

}  // namespace

std::string tracks_against_each_other(const Model& model, const TankLayout& t) {
  return fmt::format(
      "tracks drive against each other: \"{}\" (axis {} in the root frame) drives toward {}X and \"{}\" (axis {}) "
      "toward {}X for +dq",
      model.links[t.left].name, vector_text(t.left_axis), t.left_sign > 0 ? "+" : "-", model.links[t.right].name,
      vector_text(t.right_axis), t.right_sign > 0 ? "+" : "-");
}

namespace {

/// What every phase shares.
struct Suite {
  const Model& model;
  const Derived& derived;
  const TankSuiteOptions& options;
  const TankOpening& opening;
  const TankLayout& tank;  // opening.tank
  CollectingSink quiet;    // scenario builds repeat nothing the first build reported
  std::vector<CheckResult>& results;
  double g, mu, mass, weight, B;
  Eigen::Vector3d com_root;  // centre of mass in the root frame at the file pose

  Scenario scenario() { return Scenario(model, derived, opening, options, options.sim, quiet); }
  void add(CheckResult r) { results.push_back(std::move(r)); }
  void skip(std::string name, std::string reason) {
    results.push_back(skipped_check(std::move(name), std::move(reason)));
  }
  std::string name(LinkIndex i) const { return i >= 0 ? model.links[i].name : std::string("none"); }
};

Eigen::Vector3d center_of_mass_in_root(const Model& model, const Derived& derived) {
  const std::vector<Eigen::Isometry3d> X_RL = compute_root_relative_frames(model);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double mass = 0;
  for (std::size_t k = 0; k < model.links.size(); ++k) {
    sum += derived.mass[k].mass * (X_RL[k] * derived.mass[k].center_of_mass);
    mass += derived.mass[k].mass;
  }
  return sum / mass;
}

/// The inertias a simulation uses, decided from the model alone: the derived tensor, or its
/// balanced replacement where the options balance an unphysical one.
std::vector<Eigen::Matrix3d> model_inertias(const Model& model, const Derived& derived, const SimOptions& options) {
  std::vector<Eigen::Matrix3d> out;
  for (std::size_t k = 0; k < model.links.size(); ++k) {
    const Eigen::Matrix3d I = derived.mass[k].inertia;
    std::optional<Eigen::Matrix3d> balanced = options.balance_inertia ? balance_inertia(I) : std::nullopt;
    out.push_back(balanced ? *balanced : I);
  }
  return out;
}

/// The Simbody system against the derived data it was built from: a self-test of the build.
void build_self_test(Suite& s, Simulation& probe) {
  auto self = [&](CheckResult r) {
    r.self_test = true;
    s.add(std::move(r));
  };
  self(relative("system mass", probe.total_mass(), s.mass, 1e-9, "kg"));
  Eigen::Vector3d com_model = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < s.model.links.size(); ++k)
    com_model += s.derived.mass[k].mass * (as_isometry(s.derived.X_WL[k]) * s.derived.mass[k].center_of_mass);
  com_model /= s.mass;
  self(absolute("centre of mass at the file pose (distance)", (probe.center_of_mass() - com_model).norm(), 0, 1e-9,
                "m"));
  const std::vector<Eigen::Matrix3d> inertias = model_inertias(s.model, s.derived, s.options.sim);
  const Eigen::MatrixXd M = probe.mass_matrix();
  for (LinkIndex joint : {s.tank.yaw, s.tank.pitch}) {
    if (joint < 0) continue;
    const int u = probe.mobility_index(joint);
    self(relative(fmt::format("mass matrix M[{0},{0}] at q = 0", s.model.links[joint].name), M(u, u),
                  subtree_axis_inertia(s.model, s.derived, joint, {}, inertias), 1e-9, "kg·m²"));
  }
}

/// The floor slopes at which the vehicle would tip over an edge of its support polygon, sideways
/// and fore-aft: atan(distance of the COM projection from the edge / COM height). Static only: a
/// vehicle on μ = 0.5 slides (at atan μ = 26.6°) before it tips on most slopes.
std::string tip_slopes(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& com, double height,
                       double& sideways, bool& to_left) {
  double side = std::numeric_limits<double>::infinity(), fore = side;
  std::string side_to, fore_to;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i], e = polygon[(i + 1) % polygon.size()] - a;
    const Eigen::Vector2d outward = Eigen::Vector2d(e.y(), -e.x()).normalized();  // counter-clockwise hull
    const double distance = (a - com).dot(outward);
    const double slope = std::atan2(distance, height) / kDeg;
    if (std::abs(outward.y()) >= std::abs(outward.x())) {
      if (slope < side) side = slope, side_to = outward.y() > 0 ? "left" : "right";
    } else if (slope < fore) {
      fore = slope, fore_to = outward.x() > 0 ? "forward" : "backward";
    }
  }
  sideways = side;
  to_left = side_to == "left";
  return fmt::format(
      "static tip slopes (COM {:.4g} m above the floor): sideways {:.3g}° (to the {}), fore-aft {:.3g}° "
      "({}); the sideways one is checked in simulation below",
      height, side, side_to, fore, fore_to);
}

struct Stance {
  bool tracks_agree = false;
  bool com_inside = false;
};

/// The sideways tip slope checked in simulation: gravity tilted toward the nearest side edge at
/// 0.9 and 1.1 times the slope, with friction high enough that the vehicle cannot slide first.
void verify_sideways_tip(Suite& s, double slope_deg, bool to_left) {
  const std::string name = fmt::format("static stability: sideways tip slope {:.3g}° in simulation", slope_deg);
  if (!(slope_deg > 0 && slope_deg < 80)) {
    s.skip(name, "no sideways tip slope below 80°");
    return;
  }
  for (const double factor : {0.9, 1.1}) {
    const double theta = factor * slope_deg * kDeg;
    SimOptions o = s.options.sim;
    o.contact_params.friction = std::max(o.contact_params.friction, 1.2 * std::tan(theta));
    o.gravity_direction = Eigen::Vector3d(0, (to_left ? 1 : -1) * std::sin(theta), -std::cos(theta));
    Scenario sc(s.model, s.derived, s.opening, s.options, o, s.quiet);
    if (!sc) return;
    // Below the slope 0.5 s; above it until it has tipped (20°; tumbling on is stiff and
    // costly), at most 1 s.
    double roll = 0;
    const double start = sc.sim().time();
    for (int k = 1; k <= (factor < 1 ? 10 : 20) && roll < 20; ++k) {
      sc.sim().advance_to(start + 0.05 * k);
      roll = std::acos(std::clamp(sc.sim().link_pose(0).linear()(2, 2), -1.0, 1.0)) / kDeg;
    }
    const std::string label = fmt::format("{}: tilted {:.3g}° ({} the slope), roll within {} s", name,
                                          factor * slope_deg, factor < 1 ? "0.9 ×" : "1.1 ×", factor < 1 ? 0.5 : 1.0);
    s.add(factor < 1 ? at_most(label + " (stays)", roll, 5, "°") : at_least(label + " (tips)", roll, 15, "°"));
  }
}

/// Whether the tracks drive the same way, and where the centre of mass stands in the support
/// polygon.
Stance stance(Suite& s) {
  const TankLayout& t = s.tank;
  const Model& model = s.model;
  const bool same = t.left_sign == t.right_sign;
  if (same)
    s.add(verdict_check(
        "tracks drive the same way for the same dq", true,
        t.left_sign > 0
            ? "both drive toward +X of the root for +dq"
            : fmt::format("both drive toward -X of the root for +dq (\"{}\" axis {}, \"{}\" axis {}): a "
                          "consistent vehicle that drives backward for +dq",
                          s.name(t.left), vector_text(t.left_axis), s.name(t.right), vector_text(t.right_axis))));
  else
    s.add(verdict_check(
        "tracks drive the same way for the same dq", false,
        tracks_against_each_other(s.model, t) + ", so a controller's straight-drive command turns the vehicle"));
  std::vector<Eigen::Vector3d> pts = t.left_points;
  pts.insert(pts.end(), t.right_points.begin(), t.right_points.end());
  const std::vector<Eigen::Vector2d> polygon = support_polygon(pts);
  const double margin = polygon_margin(polygon, s.com_root.head<2>());
  const double height = s.com_root.z() - t.lowest_z;
  double sideways = 0;
  bool to_left = false;
  CheckResult inside = at_least("static stability: centre of mass inside the support polygon (margin)",
                                std::isfinite(margin) ? margin : -1.0, 0, "m");
  inside.passed = margin > 0;
  inside.tolerance = "> 0";
  if (!inside.passed)
    inside.note = fmt::format(
        "the centre of mass projects to ({:.4g}, {:.4g}) m, outside the support polygon [{}] "
        "(root frame); the vehicle tips over",
        s.com_root.x(), s.com_root.y(), polygon_text(polygon));
  else
    inside.note = tip_slopes(polygon, s.com_root.head<2>(), height, sideways, to_left);
  s.add(inside);
  if (inside.passed && same)
    verify_sideways_tip(s, sideways, to_left);
  else
    s.skip("static stability: sideways tip slope in simulation",
           inside.passed ? "the tracks drive against each other (see above)"
                         : "the centre of mass is outside the support polygon");
  (void)model;
  return {same, inside.passed};
}

void settle(Suite& s) {
  Scenario sc = s.scenario();
  if (!sc) return;
  sc.run(1.0);
  // Averages of contact forces mean something only at rest.
  const double height = std::max(s.com_root.z() - s.tank.lowest_z, 1e-3);
  const double bound = 1e-4 * s.weight * height;
  const double ke = sc.sim().kinetic_energy();
  s.add(at_most("settle: kinetic energy after 1 s (≤ 1e-4 × weight × height of the centre of mass)", ke, bound, "J"));
  double fz = 0, worst_ke = ke;
  int samples = 0;
  sc.run(0.5, [&](double) {
    fz += sc.sim().total_contact_force().z();
    worst_ke = std::max(worst_ke, sc.sim().kinetic_energy());
    ++samples;
  });
  if (worst_ke > bound)
    s.skip("settle: floor contact force equals the weight",
           fmt::format("the vehicle has not settled (kinetic energy up to {:.3g} J > {:.3g} J)", worst_ke, bound));
  else
    s.add(relative("settle: floor contact force equals the weight", fz / samples, s.weight, 0.01, "N"));
  const double depth = std::max(sc.sim().max_penetration(s.tank.left), sc.sim().max_penetration(s.tank.right));
  s.add(within("settle: track bottoms below the floor", depth * 1e3, 0, 0, 2, "mm"));
}

/// Straight drive with the same dq on both tracks, as a controller commands it.
void drive(Suite& s, double v) {
  const int direction = s.opening.drive_direction;
  const double expected = direction * v;
  Scenario sc = s.scenario();
  if (!sc) return;
  sc.run(0.3);
  const double yaw0 = yaw_of(sc.sim().link_pose(0));
  const Eigen::Vector3d start = sc.sim().link_pose(0).translation();
  sc.drive(v, v);
  double t90 = std::numeric_limits<double>::quiet_NaN();
  // Fine samples while the speed builds up (t90 to 1 ms), coarse ones after.
  const double t0 = sc.sim().time();
  for (int i = 1; i <= 1000 && std::isnan(t90); ++i) {
    sc.sim().advance_to(t0 + 0.001 * i);
    if (sc.com_forward_speed() * direction >= 0.9 * v) t90 = 0.001 * i;
  }
  sc.run(1.5 - (sc.sim().time() - t0));
  double speed = 0, lateral = 0;
  int samples = 0;
  sc.run(
      0.8,
      [&](double) {
        const Eigen::Vector3d hv = sc.heading_velocity();
        speed += hv.x();
        lateral += std::abs(hv.y());
        ++samples;
      },
      0.01);
  speed /= samples;
  const double distance = (sc.sim().link_pose(0).translation() - start).norm();
  const double drift = std::abs(wrap(yaw_of(sc.sim().link_pose(0)) - yaw0)) / kDeg / std::max(distance, 1e-9);
  const std::string label = fmt::format("drive dq = {:+g} on both tracks", v);
  s.add(relative(label + ": forward speed", speed, expected, 0.02, "m/s"));
  s.add(at_most(label + ": heading drift", drift, 1.0, "°/m"));
  const double t90_bound = 0.9 * v / (s.mu * s.g);  // Coulomb: acceleration ≤ μ·g
  s.add(within(label + ": centre of mass time to 90 % (≥ 0.9 × speed / (friction × g))", t90, t90_bound,
               0.99 * t90_bound, 1.3 * t90_bound, "s"));
}

/// Spin in place, each direction against its own quasi-static reference.
void spin(Suite& s, const std::vector<double>& loads, const std::string& loads_why) {
  const double u = 0.5;
  const TankLayout& t = s.tank;
  std::vector<Eigen::Vector3d> pts = t.left_points;
  pts.insert(pts.end(), t.right_points.begin(), t.right_points.end());
  const std::string layout =
      fmt::format("{}+{} contact points, B = {:.4g} m", t.left_points.size(), t.right_points.size(), s.B);
  for (int direction = 0; direction < 2; ++direction) {
    const double left = direction == 0 ? u : -u, right = -left;
    const std::string label = fmt::format(
        "spin dq_L = {:+g}, dq_R = {:+g}: yaw rate / (2 × belt speed / track spacing) ({})", left, right, layout);
    if (!loads_why.empty()) {
      s.skip(label, "no quasi-static reference: " + loads_why);
      continue;
    }
    // The belt surface moves along dq·(a_w × n_out), n_out = −Z (spec §1.4).
    std::vector<Eigen::Vector3d> belt;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const bool on_left = i < t.left_points.size();
      const Eigen::Vector3d a = on_left ? t.left_axis : t.right_axis;
      belt.push_back((on_left ? left : right) * a.cross(-Eigen::Vector3d::UnitZ()).normalized());
    }
    const SpinSolution reference = coulomb_motion(pts, loads, belt);
    if (!reference.converged) {
      s.skip(label, "the quasi-static Coulomb reference has no answer: " + reference.why);
      continue;
    }
    Scenario sc = s.scenario();
    if (!sc) return;
    sc.run(0.3);
    sc.drive(left, right);
    double omega = 0;
    int samples = 0;
    sc.run(1.0);
    sc.run(
        1.0,
        [&](double) {
          omega += sc.heading_velocity().z();
          ++samples;
        },
        0.01);
    omega /= samples;
    const double ideal = 2 * u / s.B;
    s.add(absolute(label, omega / ideal, reference.velocity.z() / ideal, 0.03, ""));
  }
}

/// Whether turning `joint` to q (the others at 0, the vehicle as it stands) brings a contact
/// point of its subtree to within 1 cm of the floor: the link that would hit it, or empty.
std::string floor_contact_at(const Model& model, const std::vector<ContactPoint>& contacts, double lowest_z,
                             LinkIndex joint, double q) {
  std::vector<double> at(model.links.size(), 0.0);
  at[joint] = q;
  const std::vector<Eigen::Isometry3d> X = compute_world_frames(model, at);
  const Eigen::Isometry3d X_root = X[0];
  for (const ContactPoint& p : contacts) {
    bool below = false;
    for (LinkIndex k = p.link; k >= 0; k = model.links[k].parent) below = below || k == joint;
    if (!below) continue;
    const double z = p.touching(X_root.inverse() * X[p.link]).z();
    if (z < lowest_z + 0.01)
      return fmt::format("(link \"{}\" would reach {:.3g} m above the floor)", model.links[p.link].name, z - lowest_z);
  }
  return {};
}

/// The pitch step of TankOpening: `no_step` says why there is none.
double pitch_step_target(const Model& model, const std::vector<ContactPoint>& contacts, const TankLayout& t,
                         std::string& no_step) {
  if (t.pitch < 0) return 0;
  const Link& pitch = model.links[t.pitch];
  const double upper = std::min(pitch.joint_range_upper, kPi), lower = std::max(pitch.joint_range_lower, -kPi);
  std::string blocked;
  for (const double side :
       upper >= -lower ? std::array<double, 2>{upper, lower} : std::array<double, 2>{lower, upper}) {
    const double q = std::clamp(2.0 / 3 * side, -30 * kDeg, 30 * kDeg);
    const std::string hit = floor_contact_at(model, contacts, t.lowest_z, t.pitch, q);
    if (q != 0 && hit.empty()) return q;
    if (!hit.empty()) blocked += fmt::format("{}at {:.4g} rad {}", blocked.empty() ? "" : "; ", q, hit);
  }
  no_step =
      blocked.empty() ? "the pitch range leaves no room for a step from 0" : "a step would hit the floor: " + blocked;
  return 0;
}

/// Pitch servo: sag under gravity and a step, against the rigid 1-DOF reference.
void pitch_servo(Suite& s) {
  const TankLayout& t = s.tank;
  const Model& model = s.model;
  if (t.pitch < 0) {
    s.skip("turret: pitch sag and step response",
           t.yaw < 0 ? "no turret yaw joint, hence no pitch joint below it"
                     : fmt::format("no revolute joint about a horizontal axis below \"{}\"", s.name(t.yaw)));
    return;
  }
  const double P = s.options.p_gain, D = s.options.d_gain;
  auto q_at = [&](double q) {
    std::vector<double> v(model.links.size(), 0.0);
    v[t.pitch] = q;
    return v;
  };
  auto tau_g = [&](double q) { return subtree_gravity_torque(model, s.derived, t.pitch, q_at(q), s.g); };
  const ServoSag sag = servo_sag(tau_g, P);
  const double I = subtree_axis_inertia(model, s.derived, t.pitch, {}, model_inertias(model, s.derived, s.options.sim));
  Scenario sc = s.scenario();
  if (!sc) return;
  sc.run(1.5);
  if (sag.converged)
    s.add(relative("turret: pitch sag under gravity (gravity torque / P gain)", sc.sim().joint_position(t.pitch), sag.q,
                   0.03, "rad"));
  else
    s.skip("turret: pitch sag under gravity (gravity torque / P gain)", "no reference: " + sag.why);
  if (t.yaw >= 0) s.add(absolute("turret: yaw holds 0", sc.sim().joint_position(t.yaw), 0, 1e-5, "rad"));
  // The step of the opening (pitch_step_target) against the rigid 1-DOF response from the
  // state the simulation reached.
  const double q_step = s.opening.pitch_step;
  if (q_step == 0) {
    s.skip("turret: pitch step response", s.opening.no_pitch_step);
    return;
  }
  const std::vector<double> times = {0.25, 0.5, 1.0, 2.0};
  const std::vector<double> expected = servo_step_response(tau_g, I, P, D, sc.sim().joint_position(t.pitch),
                                                           sc.sim().joint_velocity(t.pitch), q_step, times);
  sc.hold(t.pitch, q_step);
  double elapsed = 0;
  const double tolerance[] = {0.03, 0.02, 0.01, 0.005};
  for (std::size_t k = 0; k < times.size(); ++k) {
    sc.run(times[k] - elapsed);
    elapsed = times[k];
    s.add(relative(fmt::format("turret: pitch step to {:.4g} rad, q at {:g} s", q_step, times[k]),
                   sc.sim().joint_position(t.pitch), expected[k], tolerance[k], "rad"));
  }
}

/// Joint range enforced by stops (our choice; Choreonoid's AIST simulator does not).
void pitch_limits(Suite& s) {
  const TankLayout& t = s.tank;
  for (int side = 0; side < 2; ++side) {
    const std::string name =
        side == 0 ? "turret: pitch stays below its upper limit + 1°" : "turret: pitch stays above its lower limit − 1°";
    if (t.pitch < 0) {
      s.skip(name, "no turret pitch joint");
      continue;
    }
    const Link& pitch = s.model.links[t.pitch];
    const double limit = side == 0 ? pitch.joint_range_upper : pitch.joint_range_lower;
    if (!s.options.sim.joint_stops) {
      s.skip(name, "joint stops are off");
      continue;
    }
    if (!(std::abs(limit) < kUnlimited)) {
      s.skip(name, fmt::format("the range of \"{}\" is unlimited on this side", pitch.name));
      continue;
    }
    Scenario l = s.scenario();
    if (!l) return;
    l.run(0.3);
    const double command = side == 0 ? limit + 15 * kDeg : limit - 20 * kDeg;
    l.hold(t.pitch, command);
    double extreme = side == 0 ? -1e9 : 1e9;
    l.run(0.6, [&](double) {
      const double q = l.sim().joint_position(t.pitch);
      extreme = side == 0 ? std::max(extreme, q) : std::min(extreme, q);
    });
    const std::string label = fmt::format("{} (commanded {:.4g}°)", name, command / kDeg);
    s.add(side == 0 ? at_most(label, extreme / kDeg, limit / kDeg + 1, "°")
                    : at_least(label, extreme / kDeg, limit / kDeg - 1, "°"));
  }
}

void yaw_tracking(Suite& s) {
  const TankLayout& t = s.tank;
  if (t.yaw < 0) {
    s.skip("turret: yaw tracking, final error and chassis reaction",
           "no revolute joint about the vertical (a turret yaw axis within 2.6° of the root's z)");
    return;
  }
  // Minimum-jerk yaw 0 → 1 rad in 2 s with velocity feed-forward: the tracking error is about
  // M_yy·α_max/P (α_max = 10√3/3 · θ/T²); allow twice that.
  const double theta = 1, T = 2;
  Scenario sc = s.scenario();
  if (!sc) return;
  sc.run(0.3);
  const double t0 = sc.sim().time();
  const double chassis_yaw0 = yaw_of(sc.sim().link_pose(0));
  sc.servo(
      t.yaw, [=](double time) { return min_jerk(time - t0, theta, T); },
      [=](double time) { return min_jerk_rate(time - t0, theta, T); });
  double worst = 0;
  sc.run(
      T + 1.0,
      [&](double time) {
        worst = std::max(worst, std::abs(sc.sim().joint_position(t.yaw) - min_jerk(time, theta, T)));
      },
      0.005);
  const double M_yy =
      subtree_axis_inertia(s.model, s.derived, t.yaw, {}, model_inertias(s.model, s.derived, s.options.sim));
  const double predicted = M_yy * (10 * std::sqrt(3.0) / 3 * theta / (T * T)) / s.options.p_gain;
  s.add(at_most("turret: yaw min-jerk 1 rad / 2 s, max tracking error (2 × inertia × acceleration / P gain)", worst,
                2 * predicted, "rad"));
  s.add(absolute("turret: yaw final error", sc.sim().joint_position(t.yaw), theta, 1e-4, "rad"));
  s.add(absolute("turret: chassis yaw reaction", wrap(yaw_of(sc.sim().link_pose(0)) - chassis_yaw0), 0, 1e-3, "rad"));
}

/// No gravity, no contact, no stops, no servos: energy and momentum are conserved.
void conservation(Suite& s) {
  SimOptions free = s.options.sim;
  free.gravity = 0;
  free.contact = false;
  free.joint_stops = false;
  free.accuracy = 1e-8;
  std::unique_ptr<Simulation> sim = Simulation::build(s.model, s.derived, free, s.quiet);
  if (!sim) return;
  sim->set_root_velocity(Eigen::Vector3d(0.3, -0.2, 0.5), Eigen::Vector3d(0.1, 0.2, 0.3));
  double rate = 2;
  for (std::size_t i = 0; i < s.model.links.size(); ++i)
    if (sim->has_joint(static_cast<LinkIndex>(i))) {
      sim->set_joint_velocity(static_cast<LinkIndex>(i), rate);
      rate = rate > 0 ? -1 : 2;
    }
  const double e0 = sim->energy();
  const auto [h0, p0] = sim->central_momentum();
  double worst_e = 0, worst_h = 0, worst_p = 0;
  const double duration = 3.0;
  for (int i = 1; i <= 30; ++i) {
    sim->advance_to(duration / 30 * i);
    worst_e = std::max(worst_e, std::abs(sim->energy() - e0) / e0);
    const auto [h, p] = sim->central_momentum();
    worst_h = std::max(worst_h, (h - h0).norm() / std::max(h0.norm(), 1e-12));
    worst_p = std::max(worst_p, (p - p0).norm() / std::max(p0.norm(), 1e-12));
  }
  s.add(at_most("conservation 3 s: energy drift, relative to the initial energy", worst_e, 1e-6, ""));
  // Momentum to the same relative standard as energy: at accuracy 1e-8 both drift ~1e-8.
  s.add(at_most("conservation 3 s: angular momentum drift about the centre of mass, relative", worst_h, 1e-6, ""));
  s.add(at_most("conservation 3 s: linear momentum drift, relative", worst_p, 1e-6, ""));
}

}  // namespace

CheckResult skipped_check(std::string name, std::string reason) {
  CheckResult r{std::move(name), 0, 0, "", "", false};
  r.skipped = true;
  r.note = std::move(reason);
  return r;
}

CheckResult verdict_check(std::string name, bool passed, std::string note) {
  CheckResult r{std::move(name), 0, 0, "", "", passed};
  r.note = std::move(note);
  return r;
}

std::optional<TankLayout> find_tank(const Model& model, const Derived& /*derived*/,
                                    const std::vector<ContactPoint>& points, std::string& why) {
  const std::vector<Eigen::Isometry3d> X_RL = compute_root_relative_frames(model);
  TankLayout tank;
  std::vector<LinkIndex> tracks;
  for (std::size_t i = 0; i < model.links.size(); ++i)
    if (is_track(model.links[i])) tracks.push_back(static_cast<LinkIndex>(i));
  if (model.links.empty() || model.root().joint_type != JointType::kFree) {
    why = "the tank suite needs a free root link";
    return std::nullopt;
  }
  // Contact points in the root frame.
  std::vector<std::vector<Eigen::Vector3d>> by_link(model.links.size());
  double lowest = std::numeric_limits<double>::infinity();
  LinkIndex lowest_link = -1;
  for (const ContactPoint& p : points) {
    // Where it touches at the file pose (root frame z is up): a sphere or rim at its lowest.
    const Eigen::Vector3d x = p.touching(X_RL[p.link]);
    by_link[p.link].push_back(x);
    if (x.z() < lowest) {
      lowest = x.z();
      lowest_link = p.link;
    }
  }
  if (tracks.size() != 2) {
    // Name what stands on the floor beside the tracks: the link that should be one.
    std::string named, floor;
    for (LinkIndex k : tracks) named += (named.empty() ? "" : ", ") + ("\"" + model.links[k].name + "\"");
    for (std::size_t i = 0; i < model.links.size(); ++i) {
      if (is_track(model.links[i]) || by_link[i].empty()) continue;
      double low = std::numeric_limits<double>::infinity();
      for (const auto& p : by_link[i]) low = std::min(low, p.z());
      if (low <= lowest + 1e-3)
        floor += fmt::format("{}\"{}\" ({} joint)", floor.empty() ? "" : ", ", model.links[i].name,
                             joint_type_name(model.links[i].joint_type));
    }
    why = fmt::format("the tank suite needs exactly two pseudo_continuous_track links; the model has {}{}{}",
                      tracks.size(), named.empty() ? "" : " (" + named + ")",
                      floor.empty() ? "" : "; touching the floor but not a track: " + floor);
    return std::nullopt;
  }
  if (!std::isfinite(lowest)) {
    why = "the model has no collision geometry";
    return std::nullopt;
  }
  tank.lowest_z = lowest;
  // Forward is where +dq drives a track: a_w × Z (the belt moves along a_w × n_out, n_out = −Z).
  double lateral[2];
  int sign[2];
  Eigen::Vector3d axis[2];
  std::vector<Eigen::Vector3d> bottoms[2];
  for (int k = 0; k < 2; ++k) {
    const Link& link = model.links[tracks[k]];
    const Eigen::Vector3d a = X_RL[tracks[k]].linear() * link.joint_axis.normalized();
    axis[k] = a;
    const Eigen::Vector3d forward = a.cross(Eigen::Vector3d::UnitZ());
    if (std::abs(forward.x()) < 0.99 * forward.norm() || forward.norm() < 1e-9) {
      why = fmt::format("the axis {} of track \"{}\" (root frame) does not drive along the root's x axis (a × z = {})",
                        vector_text(a), link.name, vector_text(forward));
      return std::nullopt;
    }
    sign[k] = forward.x() > 0 ? 1 : -1;
    const std::vector<Eigen::Vector3d>& all = by_link[tracks[k]];
    if (all.empty()) {
      why = fmt::format("track \"{}\" has no collision geometry", link.name);
      return std::nullopt;
    }
    double low = std::numeric_limits<double>::infinity();
    for (const auto& p : all) low = std::min(low, p.z());
    for (const auto& p : all)
      if (p.z() <= low + 1e-6) bottoms[k].push_back(p);
    if (low > lowest + 1e-3 && tank.standing_problem.empty())
      tank.standing_problem = fmt::format(
          "track \"{}\" does not reach the floor: its lowest point is {:.4g} m above that of link \"{}\", "
          "which the vehicle stands on instead",
          link.name, low - lowest, model.links[lowest_link].name);
    lateral[k] = mean(bottoms[k]).y();
  }
  const int left = lateral[0] > lateral[1] ? 0 : 1;
  const int right = 1 - left;
  tank.left = tracks[left];
  tank.right = tracks[right];
  tank.left_sign = sign[left];
  tank.right_sign = sign[right];
  tank.left_axis = axis[left];
  tank.right_axis = axis[right];
  tank.left_points = bottoms[left];
  tank.right_points = bottoms[right];
  tank.spacing = lateral[left] - lateral[right];
  if (!(tank.spacing > 1e-6)) {
    why = "the two tracks are not side by side";
    return std::nullopt;
  }
  // Turret: the first revolute joint about the vertical, then a horizontal one below it.
  for (std::size_t i = 1; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    if (link.joint_type != JointType::kRevolute) continue;
    const Eigen::Vector3d a = X_RL[i].linear() * link.joint_axis.normalized();
    if (tank.yaw < 0 && std::abs(a.z()) > 0.999) {
      tank.yaw = static_cast<LinkIndex>(i);
    } else if (tank.yaw >= 0 && tank.pitch < 0 && std::abs(a.z()) < 1e-3) {
      for (LinkIndex k = link.parent; k >= 0; k = model.links[k].parent)
        if (k == tank.yaw) tank.pitch = static_cast<LinkIndex>(i);
    }
  }
  return tank;
}

std::optional<TankOpening> open_tank(const Model& model, const Derived& derived, const SimOptions& options,
                                     DiagnosticSink& sink, std::string& why) {
  TankOpening o;
  o.probe = Simulation::build(model, derived, options, sink);
  if (!o.probe) {
    why = "the model cannot be simulated as written (see above)";
    return std::nullopt;
  }
  o.contacts = o.probe->contact_points();
  std::optional<TankLayout> found = find_tank(model, derived, o.contacts, why);
  if (!found) return std::nullopt;
  o.tank = std::move(*found);
  o.start.translation() = Eigen::Vector3d(0, 0, -o.tank.lowest_z);
  for (std::size_t i = 0; i < model.links.size(); ++i)
    if (o.probe->has_joint(static_cast<LinkIndex>(i))) o.held_joints.push_back(static_cast<LinkIndex>(i));
  o.drive_direction = o.tank.left_sign == o.tank.right_sign ? o.tank.left_sign : 0;
  o.pitch_step = pitch_step_target(model, o.contacts, o.tank, o.no_pitch_step);
  return o;
}

std::vector<CheckResult> run_tank_suite(const Model& model, const Derived& derived, const TankSuiteOptions& options,
                                        DiagnosticSink& sink, std::string& why, TankLayout* layout) {
  std::vector<CheckResult> results;
  // The first build reports the model's findings (inertia); later ones repeat nothing.
  std::optional<TankOpening> opening = open_tank(model, derived, options.sim, sink, why);
  if (!opening) return results;
  const TankLayout& tank = opening->tank;
  if (layout) *layout = tank;
  Suite s{model,
          derived,
          options,
          *opening,
          tank,
          {},
          results,
          options.sim.gravity,
          options.sim.contact_params.friction,
          derived.total_mass,
          derived.total_mass * options.sim.gravity,
          tank.spacing,
          center_of_mass_in_root(model, derived)};
  build_self_test(s, *opening->probe);
  opening->probe.reset();
  if (!tank.standing_problem.empty()) {
    s.add(verdict_check("the vehicle stands on its two tracks", false, tank.standing_problem));
    s.skip("settle, drive, spin, turret and conservation checks", "the vehicle does not stand on its tracks");
    return results;
  }
  const Stance stands = stance(s);
  std::vector<Eigen::Vector3d> pts = tank.left_points;
  pts.insert(pts.end(), tank.right_points.begin(), tank.right_points.end());
  const StaticLoads static_loads = static_loads_on_springs(pts, s.com_root, s.weight);
  if (!stands.com_inside) {
    s.skip("settle, drive, spin and turret checks", "the centre of mass is outside the support polygon");
    conservation(s);
    return results;
  }
  settle(s);
  if (stands.tracks_agree) {
    for (double v : {0.5, 1.0}) drive(s, v);
    spin(s, static_loads.loads, static_loads.why);
  } else {
    s.skip("straight drive and spin in place", "the tracks drive against each other (see above)");
  }
  pitch_servo(s);
  pitch_limits(s);
  yaw_tracking(s);
  conservation(s);
  return results;
}

}  // namespace bodyfmt::dynamics
