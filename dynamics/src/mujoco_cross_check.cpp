// `bodysim check-tank --cross-check mujoco` (dynamics-checker.md §3, §4 T8): the settle, drive,
// spin and turret scenarios run in Simbody and in MuJoCo 2.2.2 on body2mjcf's export of the same
// model, with the tracks' belt velocity injected through mjcb_control into the friction rows'
// reference acceleration (spec §3.2). Each quantity is reported from both engines.

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/dynamics/checks.h>

#include "mjcf_writer.h"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace bodyfmt::dynamics {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;

/// What the scenarios need from an engine.
class Engine {
 public:
  virtual ~Engine() = default;
  virtual void drive(LinkIndex track, double dq) = 0;
  virtual void servo(LinkIndex joint, double p_gain, double d_gain, double q_ref) = 0;
  virtual void advance_to(double t) = 0;
  virtual double time() const = 0;
  /// Root velocity along its own heading: forward, lateral, and the world yaw rate.
  virtual Eigen::Vector3d heading_velocity() const = 0;
  virtual double joint_position(LinkIndex joint) const = 0;
  virtual double root_height() const = 0;
  virtual double floor_force() const = 0;
};

class SimbodyEngine : public Engine {
 public:
  SimbodyEngine(std::unique_ptr<Simulation> sim, double z) : sim_(std::move(sim)) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation().z() = z;
    sim_->set_root_pose(X);
  }
  void drive(LinkIndex track, double dq) override { sim_->set_track_speed(track, dq); }
  void servo(LinkIndex joint, double p, double d, double q_ref) override {
    sim_->set_servo(joint, {p, d, [q_ref](double) { return q_ref; }, nullptr, 0});
  }
  void advance_to(double t) override { sim_->advance_to(t); }
  double time() const override { return sim_->time(); }
  Eigen::Vector3d heading_velocity() const override {
    const Eigen::Isometry3d X = sim_->link_pose(0);
    const auto [omega, v] = sim_->link_velocity(0);
    return {v.dot(X.linear().col(0)), v.dot(X.linear().col(1)), omega.z()};
  }
  double joint_position(LinkIndex joint) const override { return sim_->joint_position(joint); }
  double root_height() const override { return sim_->link_pose(0).translation().z(); }
  double floor_force() const override { return sim_->total_contact_force().z(); }

 private:
  std::unique_ptr<Simulation> sim_;
};

class MujocoEngine;
MujocoEngine* g_active = nullptr;  // mjcb_control is global: one model per process (spec §6.8)

class MujocoEngine : public Engine {
 public:
  MujocoEngine(const Model& model, mjModel* m, double z) : model_(model), m_(m), d_(mj_makeData(m)) {
    track_speed_.assign(model.links.size(), 0.0);
    servo_.assign(model.links.size(), {0, 0, 0, false});
    body_.assign(model.links.size(), -1);
    joint_.assign(model.links.size(), -1);
    for (std::size_t i = 0; i < model.links.size(); ++i) {
      body_[i] = mj_name2id(m_, mjOBJ_BODY, model.links[i].name.c_str());
      joint_[i] = mj_name2id(m_, mjOBJ_JOINT, model.links[i].name.c_str());
    }
    const int root = joint_[0];
    const int a = m_->jnt_qposadr[root];
    d_->qpos[a + 2] = z;
    mj_forward(m_, d_);
    g_active = this;
    mjcb_control = &MujocoEngine::control;
  }
  ~MujocoEngine() override {
    mjcb_control = nullptr;
    g_active = nullptr;
    mj_deleteData(d_);
  }
  void drive(LinkIndex track, double dq) override { track_speed_[track] = dq; }
  void servo(LinkIndex joint, double p, double d, double q_ref) override { servo_[joint] = {p, d, q_ref, true}; }
  void advance_to(double t) override {
    while (d_->time < t - 0.5 * m_->opt.timestep) mj_step(m_, d_);
  }
  double time() const override { return d_->time; }
  Eigen::Vector3d heading_velocity() const override {
    const int body = body_[0];
    const mjtNum* R = d_->xmat + 9 * body;  // row-major
    const Eigen::Vector3d x(R[0], R[3], R[6]), y(R[1], R[4], R[7]);
    const int v = m_->jnt_dofadr[joint_[0]];
    const Eigen::Vector3d velocity(d_->qvel[v], d_->qvel[v + 1], d_->qvel[v + 2]);
    // A free joint's angular velocity is in the body frame: rotate it into the world.
    const Eigen::Vector3d w(d_->qvel[v + 3], d_->qvel[v + 4], d_->qvel[v + 5]);
    const double yaw_rate = R[6] * w.x() + R[7] * w.y() + R[8] * w.z();
    return {velocity.dot(x), velocity.dot(y), yaw_rate};
  }
  double joint_position(LinkIndex joint) const override { return d_->qpos[m_->jnt_qposadr[joint_[joint]]]; }
  double root_height() const override { return d_->qpos[m_->jnt_qposadr[joint_[0]] + 2]; }
  double floor_force() const override {
    double sum = 0;
    for (int i = 0; i < d_->ncon; ++i) {
      mjtNum f[6];
      mj_contactForce(m_, d_, i, f);
      sum += f[0] * d_->contact[i].frame[2];  // the normal's world z (floor contacts: 1)
    }
    return sum;
  }

 private:
  struct Servo {
    double p, d, q_ref;
    bool on;
  };

  static void control(const mjModel* m, mjData* d) {
    MujocoEngine* self = g_active;
    if (!self) return;
    // Joint servos.
    mju_zero(d->qfrc_applied, m->nv);
    for (std::size_t i = 0; i < self->servo_.size(); ++i) {
      const Servo& s = self->servo_[i];
      if (!s.on || self->joint_[i] < 0) continue;
      const int j = self->joint_[i];
      const double q = d->qpos[m->jnt_qposadr[j]], qd = d->qvel[m->jnt_dofadr[j]];
      d->qfrc_applied[m->jnt_dofadr[j]] = s.p * (s.q_ref - q) - s.d * qd;
    }
    // Belt velocity: the friction rows' reference velocity moves from 0 to the belt's
    // v2 − v1 = dq·normalize(a_w × n), n from geom1 to geom2, for either slot (spec §3.2).
    for (int c = 0; c < d->ncon; ++c) {
      const mjContact& con = d->contact[c];
      if (con.efc_address < 0 || con.dim < 3) continue;
      Eigen::Vector3d target = Eigen::Vector3d::Zero();
      const Eigen::Vector3d n(con.frame[0], con.frame[1], con.frame[2]);
      for (int geom : {con.geom1, con.geom2}) {
        const int body = m->geom_bodyid[geom];
        for (std::size_t i = 0; i < self->body_.size(); ++i) {
          if (self->body_[i] != body || self->track_speed_[i] == 0) continue;
          const Eigen::Vector3d a = self->model_.links[i].joint_axis.normalized();
          const mjtNum* R = d->xmat + 9 * body;
          const Eigen::Vector3d a_w(R[0] * a.x() + R[1] * a.y() + R[2] * a.z(),
                                    R[3] * a.x() + R[4] * a.y() + R[5] * a.z(),
                                    R[6] * a.x() + R[7] * a.y() + R[8] * a.z());
          const Eigen::Vector3d dir = a_w.cross(n);
          if (dir.norm() > 1e-9) target += self->track_speed_[i] * dir.normalized();
        }
      }
      if (target.isZero()) continue;
      const int adr = con.efc_address;
      for (int k = 1; k <= 2; ++k) {
        const Eigen::Vector3d t(con.frame[3 * k], con.frame[3 * k + 1], con.frame[3 * k + 2]);
        d->efc_aref[adr + k] += d->efc_KBIP[4 * (adr + k) + 1] * target.dot(t);
      }
    }
  }

  const Model& model_;
  mjModel* m_;
  mjData* d_;
  std::vector<double> track_speed_;
  std::vector<Servo> servo_;
  std::vector<int> body_, joint_;
};

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

  // body2mjcf's export, plus a floor, in a scratch folder.
  char pattern[] = "/tmp/bodysim-mujoco-XXXXXX";
  if (!mkdtemp(pattern)) {
    why = "cannot create a scratch folder for the MJCF export";
    return results;
  }
  const std::filesystem::path dir(pattern);
  mjcf::MjcfOptions mjcf_options;
  mjcf_options.balance_inertia = options.sim.balance_inertia;
  converters::OutputSet out(dir / "model.xml");
  CollectingSink export_sink;
  const bool written = mjcf::write_mjcf(model, derived, mjcf_options, out, export_sink) && out.commit(export_sink);
  for (const Diagnostic& d : export_sink.diagnostics())
    if (d.severity >= Severity::kError) sink.report(d);
  if (!written) {
    why = "body2mjcf could not export the model";
    std::filesystem::remove_all(dir);
    return results;
  }
  {
    std::ofstream scene(dir / "scene.xml");
    scene << "<mujoco model=\"bodysim cross-check\">\n  <include file=\"model.xml\"/>\n"
             "  <worldbody>\n    <geom name=\"bodysim_floor\" type=\"plane\" size=\"0 0 1\"/>\n"
             "  </worldbody>\n</mujoco>\n";
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML((dir / "scene.xml").c_str(), nullptr, error, sizeof error);
  std::filesystem::remove_all(dir);
  if (!m) {
    why = std::string("MuJoCo 2.2.2 refused the export: ") + error;
    return results;
  }
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
