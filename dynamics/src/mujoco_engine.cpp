#include "mujoco_engine.h"

#include <bodyfmt/converters/output_set.h>

#include "mjcf_writer.h"

#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

namespace bodyfmt::dynamics {
namespace {

MujocoEngine* g_active = nullptr;  // mjcb_control is global: one model per process (spec §6.8)

}  // namespace

SimbodyEngine::SimbodyEngine(std::unique_ptr<Simulation> sim, double z) : sim_(std::move(sim)) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().z() = z;
  sim_->set_root_pose(X);
}
SimbodyEngine::SimbodyEngine(std::unique_ptr<Simulation> sim, const Eigen::Isometry3d& root) : sim_(std::move(sim)) {
  sim_->set_root_pose(root);
}
void SimbodyEngine::drive(LinkIndex track, double dq) { sim_->set_track_speed(track, dq); }
void SimbodyEngine::servo(LinkIndex joint, double p, double d, double q_ref) {
  sim_->set_servo(joint, {p, d, [q_ref](double) { return q_ref; }, nullptr, 0});
}
void SimbodyEngine::advance_to(double t) { sim_->advance_to(t); }
double SimbodyEngine::time() const { return sim_->time(); }
Eigen::Vector3d SimbodyEngine::heading_velocity() const {
  const Eigen::Isometry3d X = sim_->link_pose(0);
  const auto [omega, v] = sim_->link_velocity(0);
  return {v.dot(X.linear().col(0)), v.dot(X.linear().col(1)), omega.z()};
}
double SimbodyEngine::joint_position(LinkIndex joint) const { return sim_->joint_position(joint); }
double SimbodyEngine::root_height() const { return sim_->link_pose(0).translation().z(); }
double SimbodyEngine::floor_force() const { return sim_->total_contact_force().z(); }
Eigen::Isometry3d SimbodyEngine::root_pose() const { return sim_->link_pose(0); }
double SimbodyEngine::kinetic_energy() const { return sim_->kinetic_energy(); }
double SimbodyEngine::penetration() const { return sim_->max_penetration(); }
int SimbodyEngine::contacts() const {
  int n = 0;
  for (const ContactPoint& p : sim_->contact_points()) {
    n += p.touching(sim_->link_pose(p.link)).z() < 0 ? 1 : 0;
  }
  return n;
}

MujocoEngine::MujocoEngine(const Model& model, mjModel* m, double z) : model_(model), m_(m), d_(mj_makeData(m)) {
  bind();
  const int a = m_->jnt_qposadr[joint_[0]];
  d_->qpos[a + 2] = z;
  mj_forward(m_, d_);
  g_active = this;
  mjcb_control = &MujocoEngine::control;
}
MujocoEngine::MujocoEngine(const Model& model, mjModel* m, const Eigen::Isometry3d& root)
    : model_(model), m_(m), d_(mj_makeData(m)) {
  bind();
  const int a = m_->jnt_qposadr[joint_[0]];
  const Eigen::Quaterniond q(root.linear());
  const double qpos[7] = {
      root.translation().x(), root.translation().y(), root.translation().z(), q.w(), q.x(), q.y(), q.z()};
  for (int k = 0; k < 7; ++k) d_->qpos[a + k] = qpos[k];
  mj_forward(m_, d_);
  g_active = this;
  mjcb_control = &MujocoEngine::control;
}
void MujocoEngine::bind() {
  track_speed_.assign(model_.links.size(), 0.0);
  servo_.assign(model_.links.size(), {0, 0, 0, false});
  body_.assign(model_.links.size(), -1);
  joint_.assign(model_.links.size(), -1);
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    body_[i] = mj_name2id(m_, mjOBJ_BODY, model_.links[i].name.c_str());
    joint_[i] = mj_name2id(m_, mjOBJ_JOINT, model_.links[i].name.c_str());
  }
}
MujocoEngine::~MujocoEngine() {
  mjcb_control = nullptr;
  g_active = nullptr;
  mj_deleteData(d_);
}
void MujocoEngine::drive(LinkIndex track, double dq) { track_speed_[track] = dq; }
void MujocoEngine::servo(LinkIndex joint, double p, double d, double q_ref) { servo_[joint] = {p, d, q_ref, true}; }
void MujocoEngine::advance_to(double t) {
  while (d_->time < t - 0.5 * m_->opt.timestep) mj_step(m_, d_);
}
double MujocoEngine::time() const { return d_->time; }
Eigen::Vector3d MujocoEngine::heading_velocity() const {
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
double MujocoEngine::joint_position(LinkIndex joint) const { return d_->qpos[m_->jnt_qposadr[joint_[joint]]]; }
double MujocoEngine::root_height() const { return d_->qpos[m_->jnt_qposadr[joint_[0]] + 2]; }
double MujocoEngine::floor_force() const {
  const int floor = mj_name2id(m_, mjOBJ_GEOM, "bodysim_floor");
  double sum = 0;
  for (int i = 0; i < d_->ncon; ++i) {
    if (d_->contact[i].geom1 != floor && d_->contact[i].geom2 != floor) continue;  // not the floor's
    mjtNum f[6];
    mj_contactForce(m_, d_, i, f);
    // The normal points from geom1 to geom2; MuJoCo puts the plane first.
    sum += f[0] * d_->contact[i].frame[2] * (d_->contact[i].geom1 == floor ? 1 : -1);
  }
  return sum;
}

Eigen::Isometry3d MujocoEngine::root_pose() const {
  const int a = m_->jnt_qposadr[joint_[0]];
  const mjtNum* q = d_->qpos + a;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized().toRotationMatrix();
  X.translation() = Eigen::Vector3d(q[0], q[1], q[2]);
  return X;
}
double MujocoEngine::kinetic_energy() const {
  // ½ q̇ᵀ M q̇ with the mass matrix of the last forward pass (the step's start).
  std::vector<mjtNum> Mv(m_->nv);
  mj_mulM(m_, d_, Mv.data(), d_->qvel);
  return 0.5 * mju_dot(d_->qvel, Mv.data(), m_->nv);
}
double MujocoEngine::penetration() const {
  const int floor = mj_name2id(m_, mjOBJ_GEOM, "bodysim_floor");
  double deepest = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < d_->ncon; ++i)
    if (d_->contact[i].geom1 == floor || d_->contact[i].geom2 == floor)
      deepest = std::max(deepest, -d_->contact[i].dist);
  return deepest;
}
int MujocoEngine::contacts() const {
  const int floor = mj_name2id(m_, mjOBJ_GEOM, "bodysim_floor");
  int n = 0;
  for (int i = 0; i < d_->ncon; ++i) n += d_->contact[i].geom1 == floor || d_->contact[i].geom2 == floor ? 1 : 0;
  return n;
}

void MujocoEngine::control(const mjModel* m, mjData* d) {
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

mjModel* load_mujoco_export(const Model& model, const Derived& derived, const SimOptions& options, DiagnosticSink& sink,
                            std::string& why, const ExportEdit& edit) {
  // body2mjcf's export, plus a floor, in a scratch folder.
  char pattern[] = "/tmp/bodysim-mujoco-XXXXXX";
  if (!mkdtemp(pattern)) {
    why = "cannot create a scratch folder for the MJCF export";
    return nullptr;
  }
  const std::filesystem::path dir(pattern);
  mjcf::MjcfOptions mjcf_options;
  mjcf_options.balance_inertia = options.balance_inertia;
  converters::OutputSet out(dir / "model.xml");
  CollectingSink export_sink;
  const bool written = mjcf::write_mjcf(model, derived, mjcf_options, out, export_sink) && out.commit(export_sink);
  for (const Diagnostic& d : export_sink.diagnostics())
    if (d.severity >= Severity::kError) sink.report(d);
  if (!written) {
    why = "body2mjcf could not export the model";
    std::filesystem::remove_all(dir);
    return nullptr;
  }
  if (edit && !edit(dir / "model.xml", why)) {
    std::filesystem::remove_all(dir);
    return nullptr;
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
  if (!m) why = std::string("MuJoCo 2.2.2 refused the export: ") + error;
  return m;
}

}  // namespace bodyfmt::dynamics
