// The tank suite (dynamics-checker.md §4, issue 12): settling, straight drive, spin in place,
// turret servos and joint stops, and conservation, on any model with two pseudo tracks.

#include <bodyfmt/dynamics/checks.h>

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace bodyfmt::dynamics {
namespace {

constexpr double kPi = 3.14159265358979323846;
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

/// Shared by every scenario: a fresh system standing on the floor, turret servos holding 0.
class Scenario {
 public:
  Scenario(const Model& model, const Derived& derived, const TankLayout& tank, const TankSuiteOptions& options,
           const SimOptions& sim_options, DiagnosticSink& sink)
      : tank_(tank), options_(options) {
    sim_ = Simulation::build(model, derived, sim_options, sink);
    if (!sim_) return;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(0, 0, -tank.lowest_z);
    sim_->set_root_pose(X);
    for (LinkIndex joint : {tank.yaw, tank.pitch})
      if (joint >= 0) hold(joint, 0.0);
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
  /// Track commands as forward belt speeds of the left and right track.
  void drive(double left, double right) {
    sim_->set_track_speed(tank_.left, tank_.left_sign * left);
    sim_->set_track_speed(tank_.right, tank_.right_sign * right);
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

 private:
  const TankLayout& tank_;
  const TankSuiteOptions& options_;
  std::unique_ptr<Simulation> sim_;
};

}  // namespace

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
  if (tracks.size() != 2) {
    why =
        fmt::format("the tank suite needs exactly two pseudo_continuous_track links; the model has {}", tracks.size());
    return std::nullopt;
  }
  // Contact points in the root frame.
  std::vector<std::vector<Eigen::Vector3d>> by_link(model.links.size());
  double lowest = std::numeric_limits<double>::infinity();
  for (const ContactPoint& p : points) {
    // The lowest point of a sphere contact at the file pose (root frame z is up).
    const Eigen::Vector3d x = X_RL[p.link] * p.position_in_link - Eigen::Vector3d(0, 0, p.radius);
    by_link[p.link].push_back(x);
    lowest = std::min(lowest, x.z());
  }
  if (!std::isfinite(lowest)) {
    why = "the model has no collision geometry";
    return std::nullopt;
  }
  tank.lowest_z = lowest;
  // Forward is where +dq drives a track: a_w × Z (the belt moves along a_w × n_out, n_out = −Z).
  double lateral[2];
  int sign[2];
  std::vector<Eigen::Vector3d> bottoms[2];
  for (int k = 0; k < 2; ++k) {
    const Link& link = model.links[tracks[k]];
    const Eigen::Vector3d a = X_RL[tracks[k]].linear() * link.joint_axis.normalized();
    const Eigen::Vector3d forward = a.cross(Eigen::Vector3d::UnitZ());
    if (std::abs(forward.x()) < 0.99 * forward.norm() || forward.norm() < 1e-9) {
      why = fmt::format("the axis of track \"{}\" does not drive along the root's x axis (a × z = ({:g}, {:g}, {:g}))",
                        link.name, forward.x(), forward.y(), forward.z());
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
    if (low > lowest + 1e-3) {
      why = fmt::format("track \"{}\" is not the lowest part of the model ({:g} m above it)", link.name, low - lowest);
      return std::nullopt;
    }
    lateral[k] = mean(bottoms[k]).y();
  }
  const int left = lateral[0] > lateral[1] ? 0 : 1;
  const int right = 1 - left;
  tank.left = tracks[left];
  tank.right = tracks[right];
  tank.left_sign = sign[left];
  tank.right_sign = sign[right];
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

std::vector<double> static_loads(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& com,
                                 double weight) {
  // Loads N_i = c0 + c1·x_i + c2·y_i (a rigid plate on equal springs) with ΣN = W,
  // ΣN·x = W·x_c, ΣN·y = W·y_c.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b(weight, weight * com.x(), weight * com.y());
  for (const auto& p : points) {
    const Eigen::Vector3d phi(1, p.x(), p.y());
    A += phi * phi.transpose();
  }
  const Eigen::Vector3d c = A.completeOrthogonalDecomposition().solve(b);
  std::vector<double> loads;
  for (const auto& p : points) loads.push_back(c.dot(Eigen::Vector3d(1, p.x(), p.y())));
  return loads;
}

double coulomb_yaw_rate(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& loads,
                        const std::vector<Eigen::Vector3d>& belt) {
  // Unknowns (vx, vy, ω) of the rigid vehicle; residual: net friction force and moment.
  auto residual = [&](const Eigen::Vector3d& x) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d p(points[i].x(), points[i].y());
      const Eigen::Vector2d slip(x[0] - x[2] * p.y() + belt[i].x(), x[1] + x[2] * p.x() + belt[i].y());
      const Eigen::Vector2d f = -loads[i] * slip / std::max(slip.norm(), 1e-12);
      r += Eigen::Vector3d(f.x(), f.y(), p.x() * f.y() - p.y() * f.x());
    }
    return r;
  };
  // Start from the no-slip estimate of the yaw rate, halved.
  double scale = 0;
  for (const auto& p : points) scale = std::max(scale, Eigen::Vector2d(p.x(), p.y()).norm());
  double omega0 = 0;
  for (std::size_t i = 0; i < points.size(); ++i) omega0 += (points[i].x() * belt[i].y() - points[i].y() * belt[i].x());
  omega0 /= std::max(1e-12, [&] {
    double s = 0;
    for (const auto& p : points) s += p.x() * p.x() + p.y() * p.y();
    return s;
  }());
  Eigen::Vector3d x(0, 0, 0.5 * omega0);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Eigen::Vector3d r = residual(x);
    Eigen::Matrix3d J;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d dx = Eigen::Vector3d::Zero();
      dx[k] = 1e-7 * std::max(1.0, std::abs(x[k]));
      J.col(k) = (residual(x + dx) - r) / dx[k];
    }
    Eigen::Vector3d step = J.colPivHouseholderQr().solve(-r);
    // Damped: never let the yaw rate change sign or jump by more than half.
    double damping = 1;
    while (damping > 1e-4 && residual(x + damping * step).norm() >= r.norm()) damping /= 2;
    x += damping * step;
    if (step.norm() * damping < 1e-12 * (1 + x.norm())) break;
  }
  (void)scale;
  return x[2];
}

std::vector<CheckResult> run_tank_suite(const Model& model, const Derived& derived, const TankSuiteOptions& options,
                                        DiagnosticSink& sink, std::string& why, TankLayout* layout) {
  std::vector<CheckResult> results;
  // The first build reports the model's findings (inertia); later ones repeat nothing.
  std::unique_ptr<Simulation> probe = Simulation::build(model, derived, options.sim, sink);
  if (!probe) {
    why = "the model cannot be simulated as written (see above)";
    return results;
  }
  std::optional<TankLayout> found = find_tank(model, derived, probe->contact_points(), why);
  if (!found) return results;
  const TankLayout& tank = *found;
  if (layout) *layout = tank;
  CollectingSink quiet;
  const SimOptions& base = options.sim;
  const double g = base.gravity;
  const double mu = base.contact_params.friction;
  const double mass = derived.total_mass;
  const double weight = mass * g;
  const double B = tank.spacing;

  // --- Model facts: Simbody's system against the model's derived data -------------------
  results.push_back(relative("system mass", probe->total_mass(), mass, 1e-9, "kg"));
  Eigen::Vector3d com_model = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < model.links.size(); ++k)
    com_model += derived.mass[k].mass * (as_isometry(derived.X_WL[k]) * derived.mass[k].center_of_mass);
  com_model /= mass;
  results.push_back(absolute("centre of mass at the file pose (distance)", (probe->center_of_mass() - com_model).norm(),
                             0, 1e-9, "m"));
  for (LinkIndex joint : {tank.yaw, tank.pitch}) {
    if (joint < 0) continue;
    const int u = probe->mobility_index(joint);
    const Eigen::MatrixXd M = probe->mass_matrix();
    results.push_back(relative(fmt::format("mass matrix M[{0},{0}] at q = 0", model.links[joint].name), M(u, u),
                               subtree_axis_inertia(model, derived, joint, {}, probe->link_inertias()), 1e-9, "kg·m²"));
  }

  // --- Static settling --------------------------------------------------------------------
  {
    Scenario s(model, derived, tank, options, base, quiet);
    if (!s) return results;
    double fz = 0;
    int samples = 0;
    s.run(1.5, [&](double t) {
      if (t > 1.0) {
        fz += s.sim().total_contact_force().z();
        ++samples;
      }
    });
    results.push_back(relative("settle: floor contact force = m·g", fz / samples, weight, 0.01, "N"));
    const double depth = std::max(s.sim().max_penetration(tank.left), s.sim().max_penetration(tank.right));
    results.push_back(within("settle: track bottoms below the floor", depth * 1e3, 0, 0, 2, "mm"));
  }

  // --- Straight drive -----------------------------------------------------------------------
  for (double v : {0.5, 1.0}) {
    Scenario s(model, derived, tank, options, base, quiet);
    s.run(0.5);
    const double yaw0 = yaw_of(s.sim().link_pose(0));
    const Eigen::Vector3d start = s.sim().link_pose(0).translation();
    s.drive(v, v);
    double t90 = std::numeric_limits<double>::quiet_NaN();
    double speed = 0, lateral = 0;
    int samples = 0;
    s.run(
        4.0,
        [&](double t) {
          const Eigen::Vector3d hv = s.heading_velocity();
          if (std::isnan(t90) && hv.x() >= 0.9 * v) t90 = t;
          if (t > 2.0) {
            speed += hv.x();
            lateral += std::abs(hv.y());
            ++samples;
          }
        },
        0.001);
    speed /= samples;
    const double distance = (s.sim().link_pose(0).translation() - start).norm();
    const double drift = std::abs(wrap(yaw_of(s.sim().link_pose(0)) - yaw0)) / kDeg / std::max(distance, 1e-9);
    const std::string label = fmt::format("drive {:g} m/s", v);
    results.push_back(relative(label + ": forward speed", speed, v, 0.02, "m/s"));
    results.push_back(at_most(label + ": heading drift", drift, 1.0, "°/m"));
    const double t90_bound = 0.9 * v / (mu * g);  // Coulomb: acceleration ≤ μ·g
    results.push_back(
        within(label + ": time to 90 % (≥ 0.9·v/(μ·g))", t90, t90_bound, 0.99 * t90_bound, 1.3 * t90_bound, "s"));
  }

  // --- Spin in place --------------------------------------------------------------------
  {
    const double u = 0.5;
    // The oracle: four-corner (or whatever the collision geometry gives) Coulomb contact.
    std::vector<Eigen::Vector3d> pts = tank.left_points;
    pts.insert(pts.end(), tank.right_points.begin(), tank.right_points.end());
    Eigen::Vector3d com_root = Eigen::Vector3d::Zero();
    const std::vector<Eigen::Isometry3d> X_RL = compute_root_relative_frames(model);
    for (std::size_t k = 0; k < model.links.size(); ++k)
      com_root += derived.mass[k].mass * (X_RL[k] * derived.mass[k].center_of_mass);
    com_root /= mass;
    const std::vector<double> loads = static_loads(pts, com_root, weight);
    std::vector<Eigen::Vector3d> belt;
    // Left +u, right −u: the belt surface moves against the commanded forward speed.
    for (std::size_t i = 0; i < pts.size(); ++i)
      belt.push_back(Eigen::Vector3d(i < tank.left_points.size() ? -u : u, 0, 0));
    const double omega_ideal = -2 * u / B;
    const double ratio_oracle = coulomb_yaw_rate(pts, loads, belt) / omega_ideal;
    double omega[2] = {0, 0};
    for (int direction = 0; direction < 2; ++direction) {
      Scenario s(model, derived, tank, options, base, quiet);
      s.run(0.5);
      const double sign = direction == 0 ? 1 : -1;
      s.drive(sign * u, -sign * u);
      int samples = 0;
      s.run(3.0, [&](double t) {
        if (t > 1.5) {
          omega[direction] += s.heading_velocity().z();
          ++samples;
        }
      });
      omega[direction] /= samples;
    }
    const std::string layout = fmt::format("{}+{} contact points", tank.left_points.size(), tank.right_points.size());
    results.push_back(
        at_most(fmt::format("spin L+{0:g} R-{0:g}: yaw rate sign (right turn, < 0)", u), omega[0], 0, "rad/s"));
    results.push_back(absolute(fmt::format("spin L+{0:g} R-{0:g}: ω / (2u/B) ({1}, B = {2:.4g} m)", u, layout, B),
                               omega[0] / omega_ideal, ratio_oracle, 0.03, ""));
    results.push_back(
        absolute(fmt::format("spin L-{0:g} R+{0:g}: ω / (2u/B)", u), omega[1] / -omega_ideal, ratio_oracle, 0.03, ""));
    results.push_back(at_most("spin: mirror asymmetry |ω+ + ω-| / |ω+|",
                              std::abs(omega[0] + omega[1]) / std::abs(omega[0]) * 100, 2, "%"));
  }

  // --- Turret -----------------------------------------------------------------------------
  if (tank.pitch >= 0) {
    const Link& pitch = model.links[tank.pitch];
    const double P = options.p_gain, D = options.d_gain;
    auto q_at = [&](double q) {
      std::vector<double> v(model.links.size(), 0.0);
      v[tank.pitch] = q;
      return v;
    };
    auto tau_g = [&](double q) { return subtree_gravity_torque(model, derived, tank.pitch, q_at(q), g); };
    // Sag under the servo: f(q) = τ_g(q) − P·q = 0, by Newton's method from q = 0 with steps
    // of at most 0.1 rad (the nearest root).
    double sag = 0;
    for (int i = 0; i < 200; ++i) {
      const double h = 1e-7, f = tau_g(sag) - P * sag;
      const double df = (tau_g(sag + h) - tau_g(sag - h)) / (2 * h) - P;
      if (df == 0) break;
      sag -= std::clamp(f / df, -0.1, 0.1);
    }
    const double I = subtree_axis_inertia(model, derived, tank.pitch, {}, probe->link_inertias());

    Scenario s(model, derived, tank, options, base, quiet);
    s.run(2.0);
    results.push_back(
        relative("turret: pitch sag under gravity (τ_g/P)", s.sim().joint_position(tank.pitch), sag, 0.03, "rad"));
    if (tank.yaw >= 0)
      results.push_back(absolute("turret: yaw holds 0", s.sim().joint_position(tank.yaw), 0, 1e-5, "rad"));

    // Step to two thirds of the wider side of the range (at most 30°): the rigid 1-DOF
    // response I·q̈ = P·(q_s − q) − D·q̇ + τ_g(q), integrated with RK4 from the sag.
    const double upper = std::min(pitch.joint_range_upper, kPi), lower = std::max(pitch.joint_range_lower, -kPi);
    const double side = upper >= -lower ? upper : lower;
    const double q_step = std::clamp(2.0 / 3 * side, -30 * kDeg, 30 * kDeg);
    if (q_step != 0) {
      auto rhs = [&](const Eigen::Vector2d& x) {
        return Eigen::Vector2d(x[1], (P * (q_step - x[0]) - D * x[1] + tau_g(x[0])) / I);
      };
      Eigen::Vector2d x(s.sim().joint_position(tank.pitch), s.sim().joint_velocity(tank.pitch));
      const double h = 1e-4;
      std::vector<std::pair<double, double>> expected;
      for (int i = 1; i <= 20000; ++i) {
        const Eigen::Vector2d k1 = rhs(x), k2 = rhs(x + h / 2 * k1), k3 = rhs(x + h / 2 * k2), k4 = rhs(x + h * k3);
        x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        if (i == 2500 || i == 5000 || i == 10000 || i == 20000) expected.emplace_back(i * h, x[0]);
      }
      s.hold(tank.pitch, q_step);
      double elapsed = 0;
      const double tolerance[] = {0.03, 0.02, 0.01, 0.005};
      for (std::size_t k = 0; k < expected.size(); ++k) {
        s.run(expected[k].first - elapsed);
        elapsed = expected[k].first;
        results.push_back(
            relative(fmt::format("turret: pitch step to {:.4g} rad, q at {:g} s", q_step, expected[k].first),
                     s.sim().joint_position(tank.pitch), expected[k].second, tolerance[k], "rad"));
      }
    }
    // Joint range enforced by stops (our choice; Choreonoid's AIST simulator does not).
    if (base.joint_stops) {
      for (int side = 0; side < 2; ++side) {
        const double limit = side == 0 ? pitch.joint_range_upper : pitch.joint_range_lower;
        if (!(std::abs(limit) < kUnlimited)) continue;
        Scenario l(model, derived, tank, options, base, quiet);
        l.run(0.5);
        const double command = side == 0 ? limit + 15 * kDeg : limit - 20 * kDeg;
        l.hold(tank.pitch, command);
        double extreme = side == 0 ? -1e9 : 1e9;
        l.run(1.5, [&](double) {
          const double q = l.sim().joint_position(tank.pitch);
          extreme = side == 0 ? std::max(extreme, q) : std::min(extreme, q);
        });
        if (side == 0)
          results.push_back(
              at_most(fmt::format("turret: pitch commanded {:.4g}° stays below the limit + 1°", command / kDeg),
                      extreme / kDeg, limit / kDeg + 1, "°"));
        else
          results.push_back(
              at_least(fmt::format("turret: pitch commanded {:.4g}° stays above the limit − 1°", command / kDeg),
                       extreme / kDeg, limit / kDeg - 1, "°"));
      }
    }
  }
  if (tank.yaw >= 0) {
    // Minimum-jerk yaw 0 → 1 rad in 2 s with velocity feed-forward: the tracking error is about
    // M_yy·α_max/P (α_max = 10√3/3 · θ/T²); allow twice that.
    const double theta = 1, T = 2;
    Scenario s(model, derived, tank, options, base, quiet);
    s.run(0.5);
    const double t0 = s.sim().time();
    const double chassis_yaw0 = yaw_of(s.sim().link_pose(0));
    s.servo(
        tank.yaw, [=](double t) { return min_jerk(t - t0, theta, T); },
        [=](double t) { return min_jerk_rate(t - t0, theta, T); });
    double worst = 0;
    s.run(
        T + 1.0,
        [&](double t) { worst = std::max(worst, std::abs(s.sim().joint_position(tank.yaw) - min_jerk(t, theta, T))); },
        0.002);
    const double M_yy = subtree_axis_inertia(model, derived, tank.yaw, {}, probe->link_inertias());
    const double predicted = M_yy * (10 * std::sqrt(3.0) / 3 * theta / (T * T)) / options.p_gain;
    results.push_back(
        at_most("turret: yaw min-jerk 1 rad / 2 s, max tracking error (2·M·α/P)", worst, 2 * predicted, "rad"));
    results.push_back(absolute("turret: yaw final error", s.sim().joint_position(tank.yaw), theta, 1e-4, "rad"));
    results.push_back(
        absolute("turret: chassis yaw reaction", wrap(yaw_of(s.sim().link_pose(0)) - chassis_yaw0), 0, 1e-3, "rad"));
  }

  // --- Conservation: no gravity, no contact, no stops, no servos -----------------------------
  {
    SimOptions free = base;
    free.gravity = 0;
    free.contact = false;
    free.joint_stops = false;
    free.accuracy = 1e-8;
    std::unique_ptr<Simulation> sim = Simulation::build(model, derived, free, quiet);
    if (!sim) return results;
    sim->set_root_velocity(Eigen::Vector3d(0.3, -0.2, 0.5), Eigen::Vector3d(0.1, 0.2, 0.3));
    double rate = 2;
    for (std::size_t i = 0; i < model.links.size(); ++i)
      if (sim->has_joint(static_cast<LinkIndex>(i))) {
        sim->set_joint_velocity(static_cast<LinkIndex>(i), rate);
        rate = rate > 0 ? -1 : 2;
      }
    const double e0 = sim->energy();
    const auto [h0, p0] = sim->central_momentum();
    double worst_e = 0, worst_h = 0, worst_p = 0;
    for (int i = 1; i <= 100; ++i) {
      sim->advance_to(0.05 * i);
      worst_e = std::max(worst_e, std::abs(sim->energy() - e0) / e0);
      const auto [h, p] = sim->central_momentum();
      worst_h = std::max(worst_h, (h - h0).norm() / std::max(h0.norm(), 1e-12));
      worst_p = std::max(worst_p, (p - p0).norm() / std::max(p0.norm(), 1e-12));
    }
    results.push_back(at_most("conservation 5 s: energy drift |ΔE|/E0", worst_e, 1e-6, ""));
    // Momentum to the same relative standard as energy: at accuracy 1e-8 both drift ~1e-8.
    results.push_back(at_most("conservation 5 s: angular momentum |ΔH|/|H0| (about the COM)", worst_h, 1e-6, ""));
    results.push_back(at_most("conservation 5 s: linear momentum |Δp|/|p0|", worst_p, 1e-6, ""));
  }
  return results;
}

}  // namespace bodyfmt::dynamics
