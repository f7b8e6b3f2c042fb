// body2mjcf: every export compiled by MuJoCo 2.2.2 (mj_loadXML) and compared with our model
// (Derived) at qpos0, simulation sanity, losses at their source lines, the inertia refusal,
// devices, actuators, equality constraints, and deterministic, atomic output.
#include "mjcf_writer.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/inertia.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <fmt/format.h>
#include <mujoco/mujoco.h>
#include "support/export_helpers.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;
using namespace bodyfmt;
using bodyfmt::converters::OutputSet;
using bodyfmt::mjcf::MjcfOptions;

namespace {

using bodyfmt::test::fresh_dir;
using bodyfmt::test::marked_lines;
using bodyfmt::test::read;
using bodyfmt::test::reported_lines;

const fs::path kData = fs::path(BODYFMT_TEST_DATA_DIR) / "mjcf";
const fs::path kCorpus = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid";
const fs::path kSimpleTank = fs::path(BODYFMT_EXAMPLES_DIR) / "simpletank.body";

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string quote(const fs::path& p) { return "'" + p.string() + "'"; }

struct Export {
  std::optional<Model> model;
  Derived derived;
  std::vector<Diagnostic> load_diagnostics;
  std::vector<Diagnostic> diagnostics;  // from the writer only
  fs::path xml;
  std::string text;
  bool ok = false;
};

/// Loads `body`, writes its MJCF to `dir`/model.xml (committed, meshes included).
Export export_file(const fs::path& body, const fs::path& dir, const MjcfOptions& options = {}) {
  Export e;
  CollectingSink load_sink;
  e.model = load_body(body.string(), LoadOptions{}, load_sink);
  e.load_diagnostics = load_sink.diagnostics();
  if (!e.model) return e;
  e.derived = compute_derived(*e.model, load_sink);
  e.xml = dir / "model.xml";
  OutputSet output(e.xml);
  CollectingSink sink;
  e.ok = bodyfmt::mjcf::write_mjcf(*e.model, e.derived, options, output, sink) && output.commit(sink);
  e.diagnostics = sink.diagnostics();
  if (e.ok) e.text = read(e.xml);
  return e;
}

bool has_errors(const std::vector<Diagnostic>& diagnostics) {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [](const Diagnostic& d) { return d.severity >= Severity::kError; });
}

/// mjModel + mjData at qpos0 (mj_forward), freed on scope exit.
struct Loaded {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  std::string error;
  explicit Loaded(const fs::path& xml) {
    char err[1000] = "";
    m = mj_loadXML(xml.string().c_str(), nullptr, err, sizeof err);
    error = err;
    if (m) {
      d = mj_makeData(m);
      mj_forward(m, d);
    }
  }
  ~Loaded() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
  Loaded(const Loaded&) = delete;
  Loaded& operator=(const Loaded&) = delete;
};

Eigen::Vector3d v3(const mjtNum* p) { return {p[0], p[1], p[2]}; }
Eigen::Matrix3d m3(const mjtNum* p) {  // MuJoCo matrices are row-major
  Eigen::Matrix3d R;
  R << p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8];
  return R;
}
Eigen::Matrix3d q3(const mjtNum* q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

double rel(double a, double b) { return std::abs(a - b) / std::max(1.0, std::abs(b)); }

/// The tensor our model asks MuJoCo for: the symmetrised one, or the library's balanced one
/// where MuJoCo refuses it.
Eigen::Matrix3d expected_inertia(const MassProperties& mp) {
  const Eigen::Matrix3d sym = symmetrized_inertia(mp.inertia);
  if (inertia_validity(principal_inertia(sym)).valid()) return sym;
  return balance_inertia(sym).value_or(Eigen::Matrix3d::Zero());
}

/// Compares MuJoCo's compiled model at qpos0 with our model; returns the first difference.
std::string compare(const Model& model, const Derived& derived, const mjModel* m, const mjData* d, double tol = 1e-9) {
  std::ostringstream why;
  double total = 0;
  for (int b = 0; b < m->nbody; ++b) total += m->body_mass[b];
  if (rel(total, derived.total_mass) > tol) return fmt::format("total mass {} != {}", total, derived.total_mass);
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    const int b = mj_name2id(m, mjOBJ_BODY, link.name.c_str());
    if (b < 0) return "no body " + link.name;
    const MassProperties& mp = derived.mass[i];
    if (rel(m->body_mass[b], mp.mass) > tol)
      return fmt::format("{}: mass {} != {}", link.name, m->body_mass[b], mp.mass);
    // Principal moments, and the principal frame through the tensor it rebuilds.
    const Eigen::Matrix3d I = expected_inertia(mp);
    const double scale = std::max(I.cwiseAbs().maxCoeff(), 1e-300);
    Eigen::Vector3d got = v3(m->body_inertia + 3 * b);
    std::sort(got.data(), got.data() + 3);
    const Eigen::Vector3d want = principal_inertia(I).moments;
    if ((got - want).cwiseAbs().maxCoeff() > tol * std::max(scale, 1.0))
      return fmt::format("{}: principal moments {} {} {} != {} {} {}", link.name, got[0], got[1], got[2], want[0],
                         want[1], want[2]);
    const Eigen::Matrix3d R_LI = q3(m->body_iquat + 4 * b);
    const Eigen::Matrix3d rebuilt = R_LI * v3(m->body_inertia + 3 * b).asDiagonal() * R_LI.transpose();
    if ((rebuilt - I).cwiseAbs().maxCoeff() > tol * std::max(scale, 1.0))
      return fmt::format("{}: principal frame differs by {}", link.name, (rebuilt - I).cwiseAbs().maxCoeff());
    // Frames at qpos0.
    const Eigen::AffineCompact3d& X = derived.X_WL[i];
    if ((v3(d->xpos + 3 * b) - X.translation()).cwiseAbs().maxCoeff() > tol) return link.name + ": origin differs";
    if ((m3(d->xmat + 9 * b) - X.linear()).cwiseAbs().maxCoeff() > tol) return link.name + ": orientation differs";
    if (mp.mass > 0 && (v3(d->xipos + 3 * b) - X * mp.center_of_mass).cwiseAbs().maxCoeff() > tol)
      return link.name + ": CoM differs";
    // Joints.
    const int j = mj_name2id(m, mjOBJ_JOINT, link.name.c_str());
    const bool moving = link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic;
    if (link.joint_type == JointType::kFree) {
      if (j < 0 || m->jnt_type[j] != mjJNT_FREE || m->jnt_bodyid[j] != b) return link.name + ": no free joint";
      continue;
    }
    if (!moving) {
      if (m->body_jntnum[b] != 0) return link.name + ": a fixed link has a MuJoCo joint";
      continue;
    }
    if (j < 0 || m->jnt_bodyid[j] != b || m->body_jntnum[b] != 1) return link.name + ": joint missing";
    const int type = link.joint_type == JointType::kRevolute ? mjJNT_HINGE : mjJNT_SLIDE;
    if (m->jnt_type[j] != type) return link.name + ": joint type differs";
    const Eigen::Vector3d axis = X.linear() * link.joint_axis.normalized();
    if ((v3(d->xaxis + 3 * j) - axis).cwiseAbs().maxCoeff() > tol) return link.name + ": joint axis differs";
    const bool limited = link.joint_range_lower > -kUnlimited && link.joint_range_upper < kUnlimited;
    if (static_cast<bool>(m->jnt_limited[j]) != limited) return link.name + ": limited differs";
    if (limited && (rel(m->jnt_range[2 * j], link.joint_range_lower) > tol ||
                    rel(m->jnt_range[2 * j + 1], link.joint_range_upper) > tol))
      return link.name + ": range differs";
  }
  return {};
}

/// Finite, and MuJoCo never reset the state for a bad acceleration (mj_step does that silently
/// after a warning).
bool finite_state(const mjModel* m, const mjData* d) {
  if (d->warning[mjWARN_BADQACC].number > 0) return false;
  for (int i = 0; i < m->nq; ++i)
    if (!std::isfinite(d->qpos[i])) return false;
  for (int i = 0; i < m->nv; ++i)
    if (!std::isfinite(d->qvel[i])) return false;
  return true;
}

const Diagnostic* find(const std::vector<Diagnostic>& diagnostics, const std::string& rule) {
  for (const auto& d : diagnostics)
    if (d.rule_id == rule) return &d;
  return nullptr;
}

}  // namespace

TEST_CASE("mjcf: every corpus model compiles in MuJoCo 2.2.2 with our masses, inertias, frames and joints") {
  REQUIRE(fs::exists(kCorpus));
  std::vector<fs::path> bodies;
  for (const auto& e : fs::recursive_directory_iterator(kCorpus))
    if (e.path().extension() == ".body") bodies.push_back(e.path());
  std::sort(bodies.begin(), bodies.end());
  MjcfOptions options;
  options.balance_inertia = true;
  int compared = 0, stepped = 0, balanced = 0, loops = 0;
  const fs::path dir = fresh_dir("corpus");
  for (const fs::path& body : bodies) {
    CAPTURE(body.string());
    const fs::path out = dir / fs::relative(body, kCorpus).replace_extension("");
    fs::create_directories(out);
    Export e = export_file(body, out, options);
    if (!e.model || has_errors(e.load_diagnostics)) continue;  // plugin models Choreonoid itself refuses
    REQUIRE(e.ok);
    Loaded l(e.xml);
    INFO(l.error);
    REQUIRE(l.m != nullptr);
    CHECK(compare(*e.model, e.derived, l.m, l.d) == "");
    ++compared;
    for (const auto& d : e.diagnostics)
      balanced += d.rule_id == "export-value-changed" && d.message.find("written balanced") != std::string::npos;
    // Closed loops are closed at qpos0 unless the writer said otherwise.
    const bool open_loop = std::any_of(e.diagnostics.begin(), e.diagnostics.end(), [](const Diagnostic& d) {
      return d.message.find("apart at the initial pose") != std::string::npos;
    });
    for (int r = 0; r < l.d->nefc && !open_loop; ++r) {
      if (l.d->efc_type[r] != mjCNSTR_EQUALITY) continue;
      CHECK(std::abs(l.d->efc_pos[r]) < 1e-9);
      ++loops;
    }
    if (e.model->root().joint_type == JointType::kFree) {
      for (int s = 0; s < 1000; ++s) mj_step(l.m, l.d);
      CHECK(finite_state(l.m, l.d));
      ++stepped;
    }
  }
  MESSAGE("compared " << compared << " models, stepped " << stepped << ", balanced " << balanced
                      << " links, closed-loop rows " << loops);
  CHECK(compared >= 48);  // every model with a Choreonoid reference (shared/corpus/reference)
  CHECK(stepped > 0);
  CHECK(balanced > 0);
  fs::remove_all(dir);
}

TEST_CASE("mjcf: a box dropped onto a plane comes to rest, and so does the balanced SimpleTank") {
  MjcfOptions options;
  options.balance_inertia = true;
  for (const fs::path& body : {kData / "drop.body", kSimpleTank}) {
    CAPTURE(body.string());
    const fs::path dir = fresh_dir("drop");
    Export e = export_file(body, dir, options);
    REQUIRE(e.ok);
    // The test adds the floor: a plane through the origin, as Choreonoid's floor models.
    std::string text = e.text;
    const std::string world = "<worldbody>";
    text.insert(text.find(world) + world.size(), "<geom name=\"floor\" type=\"plane\" size=\"10 10 0.1\"/>");
    const fs::path with_floor = dir / "with_floor.xml";
    std::ofstream(with_floor) << text;
    Loaded l(with_floor);
    INFO(l.error);
    REQUIRE(l.m != nullptr);
    const double start_z = l.d->xpos[3 * 1 + 2];
    for (int s = 0; s < 3000; ++s) mj_step(l.m, l.d);  // 3 s
    REQUIRE(finite_state(l.m, l.d));
    double speed = 0;
    for (int i = 0; i < l.m->nv; ++i) speed = std::max(speed, std::abs(l.d->qvel[i]));
    CHECK(speed < 1e-2);
    const double z = l.d->xpos[3 * 1 + 2];
    CHECK(z < start_z + 1e-3);
    // The box rests on a face (centre 0.1 above the floor); the tank's track bottoms are 0.1
    // below its root.
    CHECK(std::abs(z - 0.1) < 2e-3);
    fs::remove_all(dir);
  }
}

TEST_CASE("mjcf: each kind of loss is reported at its source line and commented in the output") {
  const fs::path body = kData / "losses.body";
  const fs::path dir = fresh_dir("losses");
  Export e = export_file(body, dir);
  REQUIRE(e.model);
  REQUIRE(e.ok);
  const auto want = marked_lines(body, "# loss");
  REQUIRE(want.size() == 10);
  CHECK(reported_lines(e.diagnostics, "export-loss") == want);
  for (const auto& d : e.diagnostics) CHECK(d.location.file == body.string());
  std::size_t comments = 0;
  for (std::size_t at = 0; (at = e.text.find("<!-- export-loss:", at)) != std::string::npos; ++at) ++comments;
  CHECK(comments == want.size());
  // The track stays a welded body with its geoms and its axis.
  CHECK(e.text.find("<numeric name=\"track_axis:TRACK\" size=\"3\" data=\"0 1 0\"/>") != std::string::npos);
  Loaded l(e.xml);
  INFO(l.error);
  REQUIRE(l.m != nullptr);
  CHECK(compare(*e.model, e.derived, l.m, l.d) == "");
  CHECK(l.m->body_jntnum[mj_name2id(l.m, mjOBJ_BODY, "TRACK")] == 0);
  CHECK(l.m->nnumeric == 1);
  // The flat IndexedFaceSet is only visual; the flat box got a thickness.
  int visual = 0, collision = 0;
  for (int g = 0; g < l.m->ngeom; ++g) (l.m->geom_contype[g] ? collision : visual)++;
  CHECK(visual == 4);
  CHECK(collision == 3);
  fs::remove_all(dir);
}

TEST_CASE(
    "mjcf: SimpleTank's chassis is refused with inertia-triangle, and --balance-inertia writes the library's tensor") {
  const fs::path dir = fresh_dir("tank");
  Export refused = export_file(kSimpleTank, dir);
  REQUIRE(refused.model);
  CHECK_FALSE(refused.ok);
  CHECK_FALSE(fs::exists(dir / "model.xml"));
  const Diagnostic* d = find(refused.diagnostics, "inertia-triangle");
  REQUIRE(d != nullptr);
  CHECK(d->severity == Severity::kError);
  CHECK(d->location.line == 27);
  CHECK(d->message.find("CHASSIS") != std::string::npos);
  CHECK(d->fix_hint.find("[0.20000002333333336, 0, 0, 0.20000002333333336, 0, 0.39999997666666665]") !=
        std::string::npos);

  MjcfOptions options;
  options.balance_inertia = true;
  Export e = export_file(kSimpleTank, dir, options);
  REQUIRE(e.ok);
  // A warning at the inertia's line (export-value-changed: the tensor as given is not written).
  const Diagnostic* w = nullptr;
  for (const auto& diag : e.diagnostics)
    if (diag.rule_id == "export-value-changed" && diag.location.line == 27) w = &diag;
  REQUIRE(w != nullptr);
  CHECK(w->severity == Severity::kWarning);
  CHECK(e.text.find("<!-- export-value-changed: the inertia [0.1, 0, 0, 0.1, 0, 0.5] of link \"CHASSIS\"") !=
        std::string::npos);
  // Old and new values, the same numbers bodycheck's fix hint gives.
  CHECK(w->message.find("[0.1, 0, 0, 0.1, 0, 0.5]") != std::string::npos);
  CHECK(w->message.find("[0.20000002333333336, 0, 0, 0.20000002333333336, 0, 0.39999997666666665]") !=
        std::string::npos);
  Loaded l(e.xml);
  REQUIRE(l.m != nullptr);
  const int chassis = mj_name2id(l.m, mjOBJ_BODY, "CHASSIS");
  const Eigen::Matrix3d balanced = *balance_inertia(symmetrized_inertia(e.derived.mass[0].inertia));
  Eigen::Vector3d got = v3(l.m->body_inertia + 3 * chassis);
  std::sort(got.data(), got.data() + 3);
  CHECK((got - principal_inertia(balanced).moments).cwiseAbs().maxCoeff() < 1e-12);
  // The camera faces +X of the turret (forward) with +Z up, as in Choreonoid.
  const int cam = mj_name2id(l.m, mjOBJ_CAMERA, "Camera");
  REQUIRE(cam >= 0);
  const Eigen::Matrix3d R = m3(l.d->cam_xmat + 9 * cam);
  CHECK((-R.col(2) - Eigen::Vector3d::UnitX()).norm() < 1e-12);
  CHECK((R.col(1) - Eigen::Vector3d::UnitZ()).norm() < 1e-12);

  // body2mjcf: exit 2 and nothing written by default; 0 or 1 and a file with the option.
  const std::string tool = BODYFMT_BODY2MJCF;
  const fs::path out = dir / "cli.xml";
  CHECK(run(tool + " " + quote(kSimpleTank) + " -o " + quote(out) + " 2> /dev/null") == 2);
  CHECK_FALSE(fs::exists(out));
  CHECK(run(tool + " " + quote(kSimpleTank) + " -o " + quote(out) + " --balance-inertia -q 2> /dev/null") == 1);
  CHECK(fs::exists(out));
  fs::remove_all(dir);
}

TEST_CASE("mjcf: devices, actuators, equality constraints, massless links and the initial keyframe") {
  const fs::path dir = fresh_dir("devices");
  MjcfOptions options;
  options.actuators = bodyfmt::mjcf::Actuators::kPosition;
  Export e = export_file(kData / "devices.body", dir, options);
  REQUIRE(e.ok);
  Loaded l(e.xml);
  INFO(l.error);
  REQUIRE(l.m != nullptr);
  const mjModel* m = l.m;
  // The massless moving link got the documented floor, with a warning at its mass (where
  // bodycheck reports the same defect, inertia-nonpositive-mass).
  const Diagnostic* floor = nullptr;
  for (const auto& diag : e.diagnostics)
    if (diag.rule_id == "export-value-changed" && diag.message.find("moving link \"MASSLESS\"") != std::string::npos)
      floor = &diag;
  REQUIRE(floor != nullptr);
  CHECK(floor->location.line == 86);  // MASSLESS's mass
  const int massless = mj_name2id(m, mjOBJ_BODY, "MASSLESS");
  CHECK(m->body_mass[massless] == bodyfmt::mjcf::kMinMovingMass);
  CHECK(m->body_inertia[3 * massless] == doctest::Approx(bodyfmt::mjcf::kMinMovingInertia).epsilon(1e-12));
  // Sensors in device-id order: force and torque on the FS site, the IMU's gyro and
  // accelerometer, then the gyro and the accelerometer.
  REQUIRE(m->nsensor == 6);
  const int types[] = {mjSENS_FORCE,         mjSENS_TORQUE, mjSENS_GYRO,
                       mjSENS_ACCELEROMETER, mjSENS_GYRO,   mjSENS_ACCELEROMETER};
  for (int s = 0; s < 6; ++s) CHECK(m->sensor_type[s] == types[s]);
  const int fs_site = mj_name2id(m, mjOBJ_SITE, "FS");
  REQUIRE(fs_site >= 0);
  CHECK(m->sensor_objid[0] == fs_site);
  CHECK(v3(l.d->site_xpos + 3 * fs_site).isApprox(Eigen::Vector3d(0, 0, -0.1)));
  // Camera: Choreonoid's 60° spans the shorter (horizontal) side of a 320x480 image.
  const int cam = mj_name2id(m, mjOBJ_CAMERA, "Eye");
  REQUIRE(cam >= 0);
  CHECK(m->cam_fovy[cam] == doctest::Approx(2 * std::atan(std::tan(M_PI / 6) * 480 / 320) * 180 / M_PI));
  const Eigen::Matrix3d R = m3(l.d->cam_xmat + 9 * cam);
  CHECK((-R.col(2) - Eigen::Vector3d::UnitX()).norm() < 1e-12);
  CHECK((R.col(1) - Eigen::Vector3d::UnitZ()).norm() < 1e-12);
  // The same direction through optical_frame_rotation instead of the device rotation.
  const int kinect = mj_name2id(m, mjOBJ_CAMERA, "Kinect");
  REQUIRE(kinect >= 0);
  const Eigen::Matrix3d K = m3(l.d->cam_xmat + 9 * kinect);
  CHECK((-K.col(2) - Eigen::Vector3d::UnitX()).norm() < 1e-12);
  CHECK((K.col(1) - Eigen::Vector3d::UnitZ()).norm() < 1e-12);
  // Spot light: direction and cutoff in degrees.
  REQUIRE(m->nlight == 1);
  CHECK(v3(m->light_dir).isApprox(Eigen::Vector3d(1, 0, 0)));
  CHECK(m->light_cutoff[0] == doctest::Approx(30));
  // Position actuators in joint-id order with the joint range and the effort limits.
  REQUIRE(m->nu == 5);
  CHECK(m->actuator_trnid[2 * 0] == mj_name2id(m, mjOBJ_JOINT, "LINK2"));
  CHECK(m->actuator_trnid[2 * 1] == mj_name2id(m, mjOBJ_JOINT, "LINK1"));
  CHECK(m->actuator_ctrllimited[1] == 1);
  CHECK(m->actuator_ctrlrange[2] == doctest::Approx(-M_PI / 4));
  CHECK(m->actuator_ctrlrange[3] == doctest::Approx(M_PI / 3));
  CHECK(m->actuator_forcelimited[0] == 1);
  CHECK(m->actuator_forcerange[1] == 50);
  CHECK(m->actuator_ctrllimited[2] == 0);  // WELDED: unlimited joint
  CHECK(m->actuator_forcelimited[2] == 0);
  // The weld and the ball are satisfied at qpos0; the ball holds while the model falls.
  REQUIRE(m->neq == 2);
  CHECK(m->eq_type[0] == mjEQ_WELD);
  CHECK(m->eq_type[1] == mjEQ_CONNECT);
  int rows = 0;
  for (int r = 0; r < l.d->nefc; ++r)
    if (l.d->efc_type[r] == mjCNSTR_EQUALITY) {
      CHECK(std::abs(l.d->efc_pos[r]) < 1e-12);
      ++rows;
    }
  CHECK(rows == 9);
  // The initial displacement is the "initial" keyframe (LINK1: 10°).
  REQUIRE(m->nkey == 1);
  const int j1 = mj_name2id(m, mjOBJ_JOINT, "LINK1");
  CHECK(m->key_qpos[m->jnt_qposadr[j1]] == doctest::Approx(10 * M_PI / 180));
  // 1e-5: MASSLESS carries the 1e-6 kg floor.
  CHECK(compare(*e.model, e.derived, l.m, l.d, 1e-5) == "");
  // Stepping without actuators: a position servo (kp = 1) on MASSLESS's 1e-9 kg·m² floor is
  // too stiff for a 1 ms explicit step (SUPPORT.md), the passive model is not.
  Export passive = export_file(kData / "devices.body", dir);
  REQUIRE(passive.ok);
  Loaded p(passive.xml);
  REQUIRE(p.m != nullptr);
  for (int s = 0; s < 1000; ++s) mj_step(p.m, p.d);
  CHECK(finite_state(p.m, p.d));
  fs::remove_all(dir);
}

TEST_CASE("mjcf: mesh files are found through meshdir from any working directory, and output is deterministic") {
  const fs::path a = fresh_dir("det_a"), b = fresh_dir("det_b");
  MjcfOptions options;
  options.balance_inertia = true;
  const fs::path sr1 = kCorpus / "SR1" / "SR1.body";
  for (const fs::path& body : {kSimpleTank, sr1, kData / "losses.body"}) {
    CAPTURE(body.string());
    Export first = export_file(body, a, options);
    Export second = export_file(body, b, options);
    REQUIRE(first.ok);
    REQUIRE(second.ok);
    std::map<std::string, std::string> fa, fb;
    for (const auto& f : fs::recursive_directory_iterator(a))
      if (f.is_regular_file()) fa[fs::relative(f.path(), a).string()] = read(f.path());
    for (const auto& f : fs::recursive_directory_iterator(b))
      if (f.is_regular_file()) fb[fs::relative(f.path(), b).string()] = read(f.path());
    CHECK(fa == fb);
  }
  // The tank's meshes live in assets/model/ (named after the output) beside the XML; MuJoCo
  // finds them from elsewhere.
  Export tank = export_file(kSimpleTank, a, options);
  REQUIRE(tank.ok);
  CHECK(tank.text.find("meshdir=\"assets/model\"") != std::string::npos);
  CHECK(fs::exists(a / "assets" / "model" / "TRACK_L_shape0.stl"));
  const fs::path cwd = fs::current_path();
  fs::current_path(fs::temp_directory_path());
  {
    Loaded l(a / "model.xml");
    INFO(l.error);
    CHECK(l.m != nullptr);
    if (l.m) CHECK(l.m->nmesh == 3);
  }
  fs::current_path(cwd);
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST_CASE("mjcf: a chain MuJoCo's XML reader can nest is written, a deeper one is refused before it is built") {
  const fs::path dir = fresh_dir("chain");
  for (int links : {96, 97}) {  // 100,000 links: tests/hostile (chain_100k)
    CAPTURE(links);
    std::ostringstream body;
    body << "format: ChoreonoidBody\nformat_version: 2.0\nname: Chain\nlinks:\n";
    for (int i = 0; i < links; ++i) {
      body << "  - {name: L" << i << (i ? ", parent: L" + std::to_string(i - 1) : std::string())
           << ", joint_type: " << (i ? "revolute, joint_axis: Z, joint_id: " + std::to_string(i - 1) : "free")
           << ", translation: [0, 0, 0.01], mass: 1, inertia: [0.01, 0, 0, 0.01, 0, 0.01]}\n";
    }
    const fs::path file = dir / "chain.body";
    std::ofstream(file) << body.str();
    Export e = export_file(file, dir);
    REQUIRE(e.model);
    if (links == 96) {
      REQUIRE(e.ok);
      Loaded l(e.xml);
      INFO(l.error);
      CHECK(l.m != nullptr);
      if (l.m) CHECK(l.m->nbody == 97);
    } else {
      CHECK_FALSE(e.ok);
      const Diagnostic* d = find(e.diagnostics, "export-write");
      REQUIRE(d != nullptr);
      CHECK(d->location.line == 5 + 96);  // the 97th link
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("mjcf: body2mjcf exit codes, --strict and atomic output") {
  const fs::path dir = fresh_dir("cli");
  const std::string tool = BODYFMT_BODY2MJCF;
  // 0: written, nothing lost.
  const fs::path clean = dir / "drop.xml";
  CHECK(run(tool + " " + quote(kData / "drop.body") + " -o " + quote(clean) + " 2> /dev/null") == 0);
  CHECK(fs::exists(clean));
  // 1: written with losses.
  const fs::path lossy = dir / "losses.xml";
  CHECK(run(tool + " " + quote(kData / "losses.body") + " -o " + quote(lossy) + " 2> /dev/null") == 1);
  CHECK(fs::exists(lossy));
  // 2 with --strict: nothing written, the existing file kept.
  { std::ofstream(lossy) << "old"; }
  CHECK(run(tool + " " + quote(kData / "losses.body") + " -o " + quote(lossy) + " --strict 2> /dev/null") == 2);
  CHECK(read(lossy) == "old");
  // --actuators takes one of three words.
  CHECK(run(tool + " " + quote(kData / "drop.body") + " -o " + quote(clean) + " --actuators bogus 2> /dev/null") == 2);
  fs::remove_all(dir);
}

TEST_CASE("mjcf: an empty joint or actuator range is written as the narrowest one MuJoCo accepts, with a warning") {
  const fs::path dir = fresh_dir("mjcf_empty_ranges");
  MjcfOptions options;
  options.actuators = bodyfmt::mjcf::Actuators::kPosition;
  Export e = export_file(kData / "empty_ranges.body", dir, options);
  REQUIRE(e.ok);
  const Diagnostic* changed = find(e.diagnostics, "export-value-changed");
  REQUIRE(changed != nullptr);
  CHECK(changed->location.line == 18);
  Loaded loaded(e.xml);
  INFO(loaded.error);
  REQUIRE(loaded.m != nullptr);
  const double ten_degrees = 10 * M_PI / 180;
  CHECK(loaded.m->jnt_range[2] == ten_degrees);
  CHECK(loaded.m->jnt_range[3] > ten_degrees);
  CHECK(loaded.m->jnt_range[3] - ten_degrees < 1e-15);
  CHECK(loaded.m->actuator_ctrlrange[1] - loaded.m->actuator_ctrlrange[0] < 1e-15);
  CHECK(loaded.m->actuator_forcerange[0] == 0);
}

TEST_CASE("mjcf: a mesh whose faces are flat has no collision geom, even when unused vertices span a volume") {
  const fs::path dir = fresh_dir("mjcf_flat_faces");
  Export e = export_file(kData / "flat_faces.body", dir);
  REQUIRE(e.ok);
  const Diagnostic* lost = find(e.diagnostics, "export-loss");
  REQUIRE(lost != nullptr);
  CHECK(lost->message.find("flat or degenerate IndexedFaceSet") != std::string::npos);
  CHECK(lost->location.line == 14);
  Loaded loaded(e.xml);
  INFO(loaded.error);
  REQUIRE(loaded.m != nullptr);
  int colliding = 0;
  for (int g = 0; g < loaded.m->ngeom; ++g)
    colliding += loaded.m->geom_contype[g] != 0 || loaded.m->geom_conaffinity[g] != 0;
  CHECK(colliding == 0);
}

TEST_CASE("mjcf: a spot light without a direction is reported and left out, the other lights are written") {
  const fs::path dir = fresh_dir("mjcf_light_without_direction");
  Export e = export_file(kData / "light_without_direction.body", dir);
  REQUIRE(e.ok);
  const Diagnostic* lost = find(e.diagnostics, "export-loss");
  REQUIRE(lost != nullptr);
  CHECK(lost->message.find("'Lamp' with the zero direction") != std::string::npos);
  CHECK(lost->location.line == 14);
  Loaded loaded(e.xml);
  INFO(loaded.error);
  REQUIRE(loaded.m != nullptr);
  CHECK(loaded.m->nlight == 1);
}

TEST_CASE("mjcf: a collision mesh that is exactly a box is a box geom with the mesh's corners, other meshes stay") {
  const fs::path dir = fresh_dir("mjcf_mesh_boxes");
  Export e = export_file(kData / "mesh_boxes.body", dir);
  REQUIRE(e.ok);
  CHECK(e.diagnostics.empty());  // nothing is lost: the same geometry
  Loaded loaded(e.xml);
  INFO(loaded.error);
  REQUIRE(loaded.m != nullptr);
  const mjModel* m = loaded.m;
  const mjData* d = loaded.d;
  const std::map<std::string, bool> box_expected = {{"ALIGNED", true},  {"TURNED", true},   {"OPEN", false},
                                                    {"BENT", false},    {"SHEARED", false}, {"INNER", false},
                                                    {"OVERLAP", false}, {"NINE", false},    {"COLLISION_ONLY", true}};
  for (const auto& entry : box_expected) {
    const std::string& name = entry.first;
    const bool expected = entry.second;
    CAPTURE(name);
    const int body = mj_name2id(m, mjOBJ_BODY, name.c_str());
    REQUIRE(body >= 0);
    int collision = -1, visual = -1;
    for (int g = 0; g < m->ngeom; ++g)
      if (m->geom_bodyid[g] == body) (m->geom_group[g] == 3 ? collision : visual) = g;
    REQUIRE(collision >= 0);
    REQUIRE(visual >= 0);
    CHECK((m->geom_type[collision] == mjGEOM_BOX) == expected);
    if (!expected) {
      CHECK(m->geom_type[collision] == mjGEOM_MESH);
      continue;
    }
    // The visual geom keeps the mesh (a sphere for COLLISION_ONLY, whose mesh is staged nowhere).
    if (name == "COLLISION_ONLY") {
      CHECK(m->geom_type[visual] == mjGEOM_SPHERE);
      CHECK_FALSE(fs::exists(dir / "assets" / "model" / "COLLISION_ONLY_shape0.stl"));
      continue;
    }
    REQUIRE(m->geom_type[visual] == mjGEOM_MESH);
    // As MuJoCo compiled them: every corner of the box is a vertex of the visual mesh, and
    // every vertex of the mesh a corner of the box (both in world coordinates).
    const Eigen::Vector3d box_at = v3(d->geom_xpos + 3 * collision), size = v3(m->geom_size + 3 * collision);
    const Eigen::Matrix3d box_R = m3(d->geom_xmat + 9 * collision);
    std::vector<Eigen::Vector3d> corners;
    for (int c = 0; c < 8; ++c)
      corners.push_back(box_at + box_R * Eigen::Vector3d((c & 1 ? 1 : -1) * size.x(), (c & 2 ? 1 : -1) * size.y(),
                                                         (c & 4 ? 1 : -1) * size.z()));
    const int mesh = m->geom_dataid[visual];
    const Eigen::Vector3d mesh_at = v3(d->geom_xpos + 3 * visual);
    const Eigen::Matrix3d mesh_R = m3(d->geom_xmat + 9 * visual);
    std::vector<Eigen::Vector3d> vertices;
    for (int v = 0; v < m->mesh_vertnum[mesh]; ++v) {
      const float* p = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + v);
      vertices.push_back(mesh_at + mesh_R * Eigen::Vector3d(p[0], p[1], p[2]));
    }
    auto nearest = [](const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& set) {
      double best = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& q : set) best = std::min(best, (p - q).norm());
      return best;
    };
    // MuJoCo keeps mesh vertices as floats.
    for (const Eigen::Vector3d& c : corners) CHECK(nearest(c, vertices) < 1e-7);
    for (const Eigen::Vector3d& v : vertices) CHECK(nearest(v, corners) < 1e-7);
  }
  // The turned box keeps the link's rotation and the per-axis scale (edges 0.17, 0.04, 0.03).
  const int turned = mj_name2id(m, mjOBJ_BODY, "TURNED");
  for (int g = 0; g < m->ngeom; ++g)
    if (m->geom_bodyid[g] == turned && m->geom_group[g] == 3) {
      CHECK(m->geom_size[3 * g] == doctest::Approx(0.085).epsilon(1e-12));
      CHECK(m->geom_size[3 * g + 1] == doctest::Approx(0.02).epsilon(1e-12));
      CHECK(m->geom_size[3 * g + 2] == doctest::Approx(0.03).epsilon(1e-12));
    }
  CHECK(e.text.find("a collision mesh that is exactly a box, written as a box") != std::string::npos);
}
