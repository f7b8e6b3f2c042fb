// `bodysim check-tank --cross-check mujoco` (dynamics-checker.md §3, §4 T8): the settle, drive,
// spin and turret scenarios run in Simbody and in MuJoCo 2.2.2 on body2mjcf's export of the same
// model, with the tracks' belt velocity injected through mjcb_control into the friction rows'
// reference acceleration (spec §3.2). Each quantity is reported from both engines.

#include <bodyfmt/dynamics/checks.h>

#include "mujoco_engine.h"

#include <fmt/format.h>

#include <cmath>

namespace bodyfmt::dynamics {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;

/// The scenarios' numbers from one engine.
struct Measures {
  double height = 0, floor = 0, speed = 0, t90 = 0, spin = 0, sag = 0;
  std::vector<double> step;
};

template <class Make>
Measures measure(Make make, const TankLayout& tank, const TankSuiteOptions& o, double q_step) {
  Measures r;
  auto hold = [&](Engine& e) {
    for (LinkIndex j : {tank.yaw, tank.pitch})
      if (j >= 0) e.servo(j, o.p_gain, o.d_gain, 0);
  };
  {
    auto e = make();
    hold(*e);
    e->advance_to(1.5);
    r.height = e->root_height();
    r.floor = e->floor_force();
  }
  {
    auto e = make();
    hold(*e);
    e->advance_to(0.5);
    e->drive(tank.left, tank.left_sign * 1.0);
    e->drive(tank.right, tank.right_sign * 1.0);
    r.t90 = std::numeric_limits<double>::quiet_NaN();
    int n = 0;
    for (int i = 1; i <= 4000; ++i) {
      e->advance_to(0.5 + i * 0.001);
      const double v = e->heading_velocity().x();
      if (std::isnan(r.t90) && v >= 0.9) r.t90 = i * 0.001;
      if (i > 2000) {
        r.speed += v;
        ++n;
      }
    }
    r.speed /= n;
  }
  {
    auto e = make();
    hold(*e);
    e->advance_to(0.5);
    e->drive(tank.left, tank.left_sign * 0.5);
    e->drive(tank.right, -tank.right_sign * 0.5);
    int n = 0;
    for (int i = 1; i <= 600; ++i) {
      e->advance_to(0.5 + i * 0.005);
      if (i > 300) {
        r.spin += e->heading_velocity().z();
        ++n;
      }
    }
    r.spin = r.spin / n / (-2 * 0.5 / tank.spacing);
  }
  if (tank.pitch >= 0) {
    auto e = make();
    hold(*e);
    e->advance_to(2.0);
    r.sag = e->joint_position(tank.pitch);
    e->servo(tank.pitch, o.p_gain, o.d_gain, q_step);
    for (double t : {0.25, 0.5, 1.0, 2.0}) {
      e->advance_to(2.0 + t);
      r.step.push_back(e->joint_position(tank.pitch));
    }
  }
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
  CollectingSink quiet;
  std::unique_ptr<Simulation> probe = Simulation::build(model, derived, options.sim, quiet);
  if (!probe) {
    why = "the model cannot be simulated as written (see above)";
    return results;
  }
  std::optional<TankLayout> found = find_tank(model, derived, probe->contact_points(), why);
  if (!found) return results;
  const TankLayout& tank = *found;

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

  const Link& pitch = model.links[tank.pitch >= 0 ? tank.pitch : 0];
  const double upper = std::min(pitch.joint_range_upper, kPi), lower = std::max(pitch.joint_range_lower, -kPi);
  const double q_step = std::clamp(2.0 / 3 * (upper >= -lower ? upper : lower), -30 * kDeg, 30 * kDeg);
  const double z = -tank.lowest_z;
  const Measures sb =
      measure([&] { return std::make_unique<SimbodyEngine>(Simulation::build(model, derived, options.sim, quiet), z); },
              tank, options, q_step);
  const Measures mj = measure([&] { return std::make_unique<MujocoEngine>(model, m, z); }, tank, options, q_step);
  mj_deleteModel(m);

  results.push_back(compare("settled root height", mj.height, sb.height, 0.5e-3, false, "m"));
  results.push_back(compare("settled floor force ΣN", mj.floor, sb.floor, 0.01, true, "N"));
  results.push_back(compare("drive 1 m/s: speed", mj.speed, sb.speed, 0.005, true, "m/s"));
  results.push_back(compare("drive 1 m/s: time to 90 %", mj.t90, sb.t90, 0.05, true, "s"));
  results.push_back(compare("spin L+0.5 R-0.5: ω / (2u/B)", mj.spin, sb.spin, 0.05, false, ""));
  if (tank.pitch >= 0) {
    results.push_back(compare("turret: pitch sag", mj.sag, sb.sag, 0.01, true, "rad"));
    const double at[] = {0.25, 0.5, 1.0, 2.0};
    for (std::size_t k = 0; k < sb.step.size(); ++k)
      results.push_back(compare(fmt::format("turret: pitch step to {:.4g} rad, q at {:g} s", q_step, at[k]), mj.step[k],
                                sb.step[k], 0.01, true, "rad"));
  }
  return results;
}

}  // namespace bodyfmt::dynamics
