// `bodysim check-tank --cross-check mujoco` (dynamics-checker.md §3, §4 T8): the settle, drive,
// spin and turret scenarios run in Simbody and in MuJoCo 2.2.2 on body2mjcf's export of the same
// model, with the tracks' belt velocity injected through mjcb_control into the friction rows'
// reference acceleration (spec §3.2). Each quantity is reported from both engines.

#include <bodyfmt/angles.h>
#include <bodyfmt/dynamics/checks.h>

#include "mujoco_engine.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bodyfmt::dynamics {
namespace {

constexpr double kDeg = kPi / 180;

/// The scenarios' numbers from one engine. Commands as a controller sends them: the same dq to
/// both tracks to drive, opposite ones to spin, whatever the tracks' axes.
struct Measures {
  double height = 0, floor = 0;  ///< settled 1.5 s: the root's height, ΣN averaged over the last 0.5 s
  /// Drive dq = +1 on both tracks: mean speed along the heading and yaw rate over the last
  /// 2 s, and the time to 90 % of 1 m/s in the opening's drive direction (NaN when none).
  double speed = 0, yaw_rate = 0, t90 = std::numeric_limits<double>::quiet_NaN();
  double spin = 0;  ///< ω / (2u/B) for dq_L = +u, dq_R = −u
  double sag = 0;
  std::vector<double> step;
};

constexpr double kDrive = 1.0, kSpin = 0.5;
constexpr double kStepTimes[] = {0.25, 0.5, 1.0, 2.0};

template <class Make>
Measures measure(Make make, const TankOpening& opening, const TankSuiteOptions& o) {
  const TankLayout& tank = opening.tank;
  Measures r;
  auto hold = [&](Engine& e) {
    for (LinkIndex j : opening.held_joints) e.servo(j, o.p_gain, o.d_gain, 0);
  };
  {
    auto e = make();
    hold(*e);
    e->advance_to(1.0);
    // ΣN averaged over the last 0.5 s: MuJoCo's contact forces chatter from step to step.
    for (int i = 1; i <= 100; ++i) {
      e->advance_to(1.0 + 0.005 * i);
      r.floor += e->floor_force() / 100;
    }
    r.height = e->root_height();
  }
  {
    auto e = make();
    hold(*e);
    e->advance_to(0.5);
    e->drive(tank.left, kDrive);
    e->drive(tank.right, kDrive);
    int n = 0;
    for (int i = 1; i <= 4000; ++i) {
      e->advance_to(0.5 + i * 0.001);
      const Eigen::Vector3d v = e->heading_velocity();
      if (std::isnan(r.t90) && opening.drive_direction != 0 && opening.drive_direction * v.x() >= 0.9 * kDrive)
        r.t90 = i * 0.001;
      if (i > 2000) {
        r.speed += v.x();
        r.yaw_rate += v.z();
        ++n;
      }
    }
    r.speed /= n;
    r.yaw_rate /= n;
  }
  {
    auto e = make();
    hold(*e);
    e->advance_to(0.5);
    e->drive(tank.left, kSpin);
    e->drive(tank.right, -kSpin);
    int n = 0;
    for (int i = 1; i <= 600; ++i) {
      e->advance_to(0.5 + i * 0.005);
      if (i > 300) {
        r.spin += e->heading_velocity().z();
        ++n;
      }
    }
    r.spin = r.spin / n / (2 * kSpin / tank.spacing);
  }
  if (tank.pitch >= 0) {
    auto e = make();
    hold(*e);
    e->advance_to(2.0);
    r.sag = e->joint_position(tank.pitch);
    if (opening.pitch_step != 0) {
      e->servo(tank.pitch, o.p_gain, o.d_gain, opening.pitch_step);
      for (double t : kStepTimes) {
        e->advance_to(2.0 + t);
        r.step.push_back(e->joint_position(tank.pitch));
      }
    }
  }
  return r;
}

/// Whether the same +dq on both tracks drives the vehicle straight in one engine: its heading
/// drift |ω|/|v| against the suite's bound of 1°/m, the cause named when it turns.
CheckResult drives_straight(const std::string& engine, const Measures& m, const Model& model,
                            const TankOpening& opening) {
  const TankLayout& t = opening.tank;
  const double drift = std::abs(m.yaw_rate) / kDeg / std::max(std::abs(m.speed), 1e-9);
  CheckResult r{fmt::format("{}: drive dq = {:+g} on both tracks: heading drift", engine, kDrive),
                drift,
                1.0,
                "°/m",
                "≤ expected",
                std::isfinite(drift) && drift <= 1.0};
  if (!r.passed && opening.drive_direction == 0)
    r.note = tracks_against_each_other(model, t) +
             fmt::format("; the vehicle turns at {:.4g} rad/s ({:.4g} m/s along its heading)", m.yaw_rate, m.speed);
  else if (!r.passed)
    r.note = fmt::format(
        "the vehicle turns at {:.4g} rad/s ({:.4g} m/s along its heading) although its tracks' axes "
        "agree",
        m.yaw_rate, m.speed);
  else if (opening.drive_direction < 0)
    r.note = fmt::format(
        "drives backward for +dq ({:.4g} m/s): a consistent vehicle whose tracks both point the "
        "other way",
        m.speed);
  return r;
}

CheckResult compare(std::string name, double mujoco, double simbody, double tolerance, bool relative,
                    std::string unit) {
  CheckResult c{"MuJoCo vs Simbody: " + std::move(name),
                mujoco,
                simbody,
                unit,
                relative ? fmt::format("±{:g} %", tolerance * 100) : fmt::format("±{:g} {}", tolerance, unit),
                false};
  const double allowed = relative ? tolerance * std::abs(simbody) : tolerance;
  c.passed = std::isfinite(mujoco) && std::abs(mujoco - simbody) <= allowed;
  return c;
}

}  // namespace

std::vector<CheckResult> run_mujoco_cross_check(const Model& model, const Derived& derived,
                                                const TankSuiteOptions& options, DiagnosticSink& sink,
                                                std::string& why) {
  std::vector<CheckResult> results;
  CollectingSink quiet;  // the suite's opening reported the model's findings
  std::optional<TankOpening> opening = open_tank(model, derived, options.sim, quiet, why);
  if (!opening) return results;
  opening->probe.reset();
  const TankLayout& tank = opening->tank;

  mjModel* m = load_mujoco_export(model, derived, options.sim, sink, why);
  if (!m) return results;
  // As in Choreonoid's MuJoCo plugin: elliptic cones (the belt injection needs them), μ on
  // every geom (MuJoCo takes the larger of a pair), and only model–floor contacts, as in Simbody.
  m->opt.cone = mjCONE_ELLIPTIC;
  m->opt.integrator = mjINT_EULER;
  m->opt.timestep = 0.001;
  const int floor = mj_name2id(m, mjOBJ_GEOM, "bodysim_floor");
  for (int g = 0; g < m->ngeom; ++g) {
    m->geom_friction[3 * g] = options.sim.contact_params.friction;
    m->geom_condim[g] = 3;
    const bool collides = m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0;
    m->geom_contype[g] = g == floor ? 1 : 0;
    m->geom_conaffinity[g] = g == floor ? 0 : (collides ? 1 : 0);
  }

  const double z = opening->start.translation().z();
  const Measures sb =
      measure([&] { return std::make_unique<SimbodyEngine>(Simulation::build(model, derived, options.sim, quiet), z); },
              *opening, options);
  const Measures mj = measure([&] { return std::make_unique<MujocoEngine>(model, m, z); }, *opening, options);
  mj_deleteModel(m);

  results.push_back(compare("settled root height", mj.height, sb.height, 0.5e-3, false, "m"));
  results.push_back(compare("settled floor force ΣN", mj.floor, sb.floor, 0.01, true, "N"));
  const std::string drive = fmt::format("drive dq = {:+g} on both tracks", kDrive);
  const CheckResult straight_sb = drives_straight("Simbody", sb, model, *opening);
  const CheckResult straight_mj = drives_straight("MuJoCo", mj, model, *opening);
  results.push_back(straight_sb);
  results.push_back(straight_mj);
  if (straight_sb.passed && straight_mj.passed) {
    results.push_back(compare(drive + ": speed", mj.speed, sb.speed, 0.005, true, "m/s"));
    results.push_back(compare(drive + ": time to 90 %", mj.t90, sb.t90, 0.05, true, "s"));
  } else {
    // The vehicle turns: what both engines can still agree on is how fast.
    results.push_back(compare(drive + ": yaw rate / (2 × dq / track spacing)",
                              mj.yaw_rate / (2 * kDrive / tank.spacing), sb.yaw_rate / (2 * kDrive / tank.spacing),
                              0.05, false, ""));
    results.push_back(skipped_check("MuJoCo vs Simbody: " + drive + ": speed and time to 90 %",
                                    "the vehicle turns instead of driving straight (see above)"));
  }
  results.push_back(compare(
      fmt::format("spin dq_L = {:+g}, dq_R = {:+g}: yaw rate / (2 × belt speed / track spacing)", kSpin, -kSpin),
      mj.spin, sb.spin, 0.05, false, ""));
  if (tank.pitch >= 0) {
    results.push_back(compare("turret: pitch sag", mj.sag, sb.sag, 0.01, true, "rad"));
    if (opening->pitch_step == 0)
      results.push_back(skipped_check("MuJoCo vs Simbody: turret: pitch step response", opening->no_pitch_step));
    for (std::size_t k = 0; k < sb.step.size(); ++k)
      results.push_back(
          compare(fmt::format("turret: pitch step to {:.4g} rad, q at {:g} s", opening->pitch_step, kStepTimes[k]),
                  mj.step[k], sb.step[k], 0.01, true, "rad"));
  }
  return results;
}

}  // namespace bodyfmt::dynamics
