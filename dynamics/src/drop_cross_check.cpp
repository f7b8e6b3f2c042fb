// `bodysim check --cross-check mujoco` (dynamics-checker.md §4 G5 and T8): the locked-joint drop
// and settle in Simbody and in MuJoCo 2.2.2 on body2mjcf's export of the same model.

#include <bodyfmt/dynamics/drop_cross_check.h>

#include "mujoco_engine.h"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>

namespace bodyfmt::dynamics {
namespace {

constexpr double kDrop = 0.02;        // m, as the generic locked drop
constexpr double kDuration = 3.0;     // s, as the generic locked drop
constexpr double kSample = 0.001;     // s: MuJoCo's step
constexpr double kForceWindow = 0.5;  // s: ΣN is averaged over the end of the run
// T8 tolerances (spec §4): settled height 0.5 mm, ΣN 1 %; the settle time is a time to a
// threshold, like T5's t90 (5 %). T8 has no line for orientation: the settle's own bound on
// turning (T3: |Δyaw| < 1e-3 rad) is used for the whole rotation.
constexpr double kHeightTolerance = 0.5e-3;
constexpr double kForceTolerance = 0.01;
constexpr double kSettleTolerance = 0.05;
constexpr double kOrientationTolerance = 1e-3;
// A resting body does not turn by itself: the root's turn over the last kTurnWindow, per second.
constexpr double kRestTurnRate = 1e-4;
constexpr double kTurnWindow = 0.1;  // s: the turn rate at rest is measured over the end of the run
// Up directions further apart than this (rad) are rests on different faces after a tumble.
constexpr double kOtherFace = 0.1;

double angle_of(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle(); }

std::string numbers(const Eigen::Vector3d& v) { return fmt::format("{:.17g} {:.17g} {:.17g}", v.x(), v.y(), v.z()); }

bool read_vector(const tinyxml2::XMLElement* e, const char* name, double* out, int n) {
  const char* text = e->Attribute(name);
  if (!text) return false;
  char* end = nullptr;
  for (int k = 0; k < n; ++k) {
    out[k] = std::strtod(text, &end);
    if (end == text) return false;
    text = end;
  }
  return true;
}

/// Welds every joint of the export at its initial position, as Simulation does with
/// lock_joints: each hinge or slide of a body is removed (MuJoCo welds a body without joints to
/// its parent) and the body's pose takes the joint's initial displacement. The keyframe,
/// actuators and equality constraints referred to the joints, or to bodies now welded into one
/// rigid body; they go too. A rigid body does not collide with itself (MuJoCo skips pairs within
/// a weld group), so the model's self-collision setting does not matter here. A free joint
/// below the root is locked too (see below).
bool weld_joints(const Model& model, const std::filesystem::path& file, std::string& why) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(file.c_str()) != tinyxml2::XML_SUCCESS) {
    why = std::string("cannot read the MJCF export: ") + doc.ErrorStr();
    return false;
  }
  tinyxml2::XMLElement* root = doc.RootElement();
  for (const char* section : {"keyframe", "actuator", "equality"})
    while (tinyxml2::XMLElement* e = root->FirstChildElement(section)) root->DeleteChild(e);
  std::map<std::string, const Link*> links;
  for (const Link& link : model.links) links[link.name] = &link;
  std::vector<tinyxml2::XMLElement*> stack;
  if (tinyxml2::XMLElement* world = root->FirstChildElement("worldbody")) stack.push_back(world);
  while (!stack.empty()) {
    tinyxml2::XMLElement* body = stack.back();
    stack.pop_back();
    for (tinyxml2::XMLElement* c = body->FirstChildElement("body"); c; c = c->NextSiblingElement("body"))
      stack.push_back(c);
    while (tinyxml2::XMLElement* joint = body->FirstChildElement("joint")) {
      const char* name = body->Attribute("name");
      const auto link = links.find(name ? name : "");
      if (link == links.end()) {
        why = fmt::format("the MJCF body \"{}\" is no link of the model", name ? name : "");
        return false;
      }
      const double q0 = link->second->initial_displacement;
      if (q0 != 0) {
        double p[3] = {0, 0, 0}, a[3] = {0, 0, 1}, x[3] = {0, 0, 0}, q[4] = {1, 0, 0, 0};
        read_vector(joint, "pos", p, 3);
        read_vector(joint, "axis", a, 3);
        read_vector(body, "pos", x, 3);
        read_vector(body, "quat", q, 4);
        const Eigen::Vector3d pj(p[0], p[1], p[2]), axis = Eigen::Vector3d(a[0], a[1], a[2]).normalized();
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
        X.translation() = Eigen::Vector3d(x[0], x[1], x[2]);
        Eigen::Isometry3d J = Eigen::Isometry3d::Identity();
        const char* type = joint->Attribute("type");
        if (type && std::string(type) == "slide") {
          J.translation() = q0 * axis;
        } else {
          J.linear() = Eigen::AngleAxisd(q0, axis).toRotationMatrix();
          J.translation() = pj - J.linear() * pj;  // about the joint's position
        }
        X = X * J;
        const Eigen::Quaterniond r(X.linear());
        body->SetAttribute("pos", numbers(X.translation()).c_str());
        body->SetAttribute("quat", fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}", r.w(), r.x(), r.y(), r.z()).c_str());
      }
      body->DeleteChild(joint);
    }
  }
  // A link with a free joint below the root is a top-level body of the export (MuJoCo has no
  // free joint inside a tree); Simulation welds it to its parent, and so does this.
  std::map<std::string, tinyxml2::XMLElement*> bodies;
  std::vector<tinyxml2::XMLElement*> all;
  if (tinyxml2::XMLElement* world = root->FirstChildElement("worldbody")) all.push_back(world);
  for (std::size_t k = 0; k < all.size(); ++k) {
    for (tinyxml2::XMLElement* c = all[k]->FirstChildElement("body"); c; c = c->NextSiblingElement("body")) {
      all.push_back(c);
      if (const char* name = c->Attribute("name")) bodies[name] = c;
    }
  }
  for (std::size_t i = 1; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    if (link.joint_type != JointType::kFree || link.parent < 0) continue;
    const auto body = bodies.find(link.name), parent = bodies.find(model.links[link.parent].name);
    if (body == bodies.end() || parent == bodies.end()) {
      why = fmt::format("the MJCF export has no body for link \"{}\" or its parent", link.name);
      return false;
    }
    tinyxml2::XMLElement* b = body->second;
    while (tinyxml2::XMLElement* free = b->FirstChildElement("freejoint")) b->DeleteChild(free);
    for (tinyxml2::XMLElement* j = b->FirstChildElement("joint"); j;) {
      tinyxml2::XMLElement* next = j->NextSiblingElement("joint");
      if (const char* type = j->Attribute("type"); type && std::string(type) == "free") b->DeleteChild(j);
      j = next;
    }
    const Eigen::Isometry3d X = as_isometry(link.X_PL);
    const Eigen::Quaterniond r(X.linear());
    b->SetAttribute("pos", numbers(X.translation()).c_str());
    b->SetAttribute("quat", fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}", r.w(), r.x(), r.y(), r.z()).c_str());
    parent->second->InsertEndChild(b);
  }
  if (doc.SaveFile(file.c_str()) != tinyxml2::XML_SUCCESS) {
    why = std::string("cannot write the welded MJCF export: ") + doc.ErrorStr();
    return false;
  }
  return true;
}

struct Sample {
  double t, z;
  Eigen::Matrix3d R;
  double force;
  int contacts;
  /// With the model's contact points: how many touch the floor.
  int touching = 0;
};

/// The model's contact points in the root's frame (rigid there while the joints are locked):
/// each one's link is the root.
using SupportPoint = ContactPoint;

/// The largest distance between two of `points` seen from above, and the support's narrowest
/// width (the smallest, over the convex hull's edges, of the farthest corner from the edge's
/// line; the span when the hull is a point or a line): the convex hull of their horizontal
/// positions, then its corners.
double horizontal_span(std::vector<Eigen::Vector2d> points, double* width = nullptr, Eigen::Vector2d* line = nullptr) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 2) return 0;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k);
  double span = 0;
  for (std::size_t a = 0; a < hull.size(); ++a)
    for (std::size_t b = a + 1; b < hull.size(); ++b)
      if ((hull[a] - hull[b]).norm() > span) {
        span = (hull[a] - hull[b]).norm();
        // Collinear points leave two corners (the first repeated): a line along the span.
        if (line && hull.size() < 4) *line = (hull[a] - hull[b]) / span;
      }
  if (width) {
    *width = span;
    if (hull.size() >= 4) {  // a closed hull of three corners or more (the last repeats the first)
      for (std::size_t e = 0; e + 1 < hull.size(); ++e) {
        const Eigen::Vector2d edge = hull[e + 1] - hull[e];
        if (edge.norm() == 0) continue;
        double farthest = 0;
        for (const Eigen::Vector2d& c : hull)
          farthest = std::max(farthest, std::abs(cross(hull[e], hull[e + 1], c)) / edge.norm());
        *width = std::min(*width, farthest);
      }
    }
  }
  return span;
}

/// Runs one engine's drop. With `points` (the model's contact points), the support the model
/// comes to rest on is measured too.
template <class Make>
DropMeasures drop(Make make, const Eigen::Isometry3d& start, const std::vector<SupportPoint>& points = {}) {
  auto engine = make();
  std::vector<Sample> samples;
  const int n = static_cast<int>(std::lround(kDuration / kSample));
  samples.reserve(n);
  // Per contact point: its height at the previous sample, and when it first touched the floor
  // (-1: not yet) and how fast it came down then.
  std::vector<double> previous_z, descent(points.size(), 0.0), landed(points.size(), -1.0),
      landing_speed(points.size(), 0.0);
  for (const SupportPoint& p : points) previous_z.push_back(p.touching(start).z());
  for (int i = 1; i <= n; ++i) {
    engine->advance_to(i * kSample);
    const Eigen::Isometry3d X = engine->root_pose();
    const bool late = i * kSample > kDuration - kForceWindow + 1e-9;
    samples.push_back(
        {i * kSample, X.translation().z(), X.linear(), engine->floor_force(), late ? engine->contacts() : 0});
    Sample& s = samples.back();
    for (std::size_t k = 0; k < points.size(); ++k) {
      const double z = points[k].touching(X).z();
      const bool touches = z < 0;
      s.touching += touches ? 1 : 0;
      const double falling = (previous_z[k] - z) / kSample;
      if (touches && landed[k] < 0) {
        landed[k] = s.t;
        landing_speed[k] = std::max(falling, descent[k]);  // the contact only slows it
      }
      descent[k] = falling;
      previous_z[k] = z;
    }
  }
  DropMeasures r;
  const Sample& end = samples.back();
  r.height = end.z;
  r.rotation = end.R;
  r.turned = angle_of(end.R * start.linear().transpose());
  int counted = 0;
  r.contacts_min = std::numeric_limits<int>::max();
  for (const Sample& s : samples)
    if (s.t > kDuration - kForceWindow + 1e-9) {
      r.floor_force += s.force;
      r.contacts_min = std::min(r.contacts_min, s.contacts);
      r.contacts_max = std::max(r.contacts_max, s.contacts);
      ++counted;
    }
  r.floor_force /= std::max(counted, 1);
  // Settled: the pose stays within the T8 bands of where it comes to rest.
  r.settle_time = 0;
  for (const Sample& s : samples) {
    const bool turning = angle_of(s.R * end.R.transpose()) > kOrientationTolerance;
    if (std::abs(s.z - end.z) > kHeightTolerance || turning) r.settle_time = s.t;
    if (turning) r.orientation_settle = s.t;
  }
  // How fast it turns at the end: over the last 0.1 s, where a creep goes on at its pace and
  // the last of a settling has died out (a 199 kg post on a 1.4 m support still turned
  // 0.8 mrad in MuJoCo over the 0.49 s after it came within 1e-3 rad of its rest).
  const Sample& window_start =
      samples[samples.size() - 1 - static_cast<std::size_t>(std::lround(kTurnWindow / kSample))];
  r.turn_rate = angle_of(end.R * window_start.R.transpose()) / (end.t - window_start.t);
  for (const Sample& s : samples)
    if (s.force > 0) {
      r.first_contact = s.t;
      break;
    }
  bool touched = false;
  for (const Sample& s : samples) {
    r.impact_sink = std::max(r.impact_sink, end.z - s.z);
    touched = touched || s.force > 0;
    if (touched) r.rebound = std::max(r.rebound, s.z - end.z);
  }
  if (!points.empty()) {
    // The support it rests on: the points that touch the floor at the end, how far apart, and
    // when the last of them came down onto the floor for the first time, how fast. Landing
    // tilted from its rest (more than the orientation band at first contact), it has tipped
    // onto that support since.
    std::vector<Eigen::Vector2d> footprint;
    for (std::size_t k = 0; k < points.size(); ++k) {
      Eigen::Isometry3d at_end = Eigen::Isometry3d::Identity();  // heights and spans
      at_end.linear() = end.R;
      at_end.translation().z() = end.z;
      const Eigen::Vector3d x = points[k].touching(at_end);
      if (x.z() >= 0 || landed[k] < 0) continue;
      footprint.emplace_back(x.x(), x.y());
      if (landed[k] > r.support_time) {
        r.support_time = landed[k];
        r.support_speed = landing_speed[k];
      }
    }
    r.support_points = static_cast<int>(footprint.size());
    Eigen::Vector2d line = Eigen::Vector2d::Zero();
    r.support_span = horizontal_span(std::move(footprint), &r.support_width, &line);
    r.support_line = end.R.transpose() * Eigen::Vector3d(line.x(), line.y(), 0);
    for (const Sample& s : samples)
      if (s.t >= r.first_contact) {
        r.tipped = angle_of(s.R * end.R.transpose()) > kOrientationTolerance;
        break;
      }
  }
  r.kinetic_energy = engine->kinetic_energy();
  r.penetration = engine->penetration();
  r.contacts = engine->contacts();
  return r;
}

/// MuJoCo's contact as the linear system it is once the penetration exceeds solimp's width
/// (impedance d = dmax): r̈ = d·(−b·ṙ − k·r), k = 1/(dmax²·τ²·ζ²), b = 2/(dmax·τ) (MuJoCo's
/// Computation chapter, "soft constraints"). From an impact at speed v, the time until the
/// penetration stays within `band` of rest.
double mujoco_relaxation(double time_constant, double damping_ratio, double dmax, double speed, double band) {
  const double k = 1 / (dmax * dmax * time_constant * time_constant * damping_ratio * damping_ratio);
  const double b = 2 / (dmax * time_constant);
  double x = 0, v = speed, last = 0;
  const double dt = 1e-5;
  for (double t = dt; t < 2.0; t += dt) {
    const double a = dmax * (-b * v - k * x);
    v += a * dt;
    x += v * dt;
    if (std::abs(x) > band) last = t;
  }
  return last;
}

CheckResult compare(std::string name, double mujoco, double simbody, double allowed, std::string unit,
                    std::string tolerance) {
  CheckResult c{"MuJoCo vs Simbody, drop 2 cm, joints locked: " + std::move(name),
                mujoco,
                simbody,
                std::move(unit),
                std::move(tolerance),
                false};
  c.passed = std::isfinite(mujoco) && std::abs(mujoco - simbody) <= allowed;
  return c;
}

}  // namespace

std::vector<CheckResult> run_drop_cross_check(const Model& model, const Derived& derived,
                                              const DropCrossCheckOptions& options, DiagnosticSink& sink,
                                              std::string& why, DropCrossCheckReport* report) {
  std::vector<CheckResult> results;
  if (model.root().joint_type != JointType::kFree) {
    why = "the MuJoCo cross-check drops a model with a free root; the root of this one is fixed";
    return results;
  }
  SimOptions locked = options.sim;
  locked.lock_joints = true;
  // What building the system reports (a balanced inertia) the generic checks have said
  // already; it is passed on only when the system cannot be built.
  CollectingSink quiet;
  std::unique_ptr<Simulation> probe = Simulation::build(model, derived, locked, quiet);
  if (!probe) {
    for (const Diagnostic& d : quiet.diagnostics()) sink.report(d);
    why = "the model cannot be simulated as written (see above)";
    return results;
  }
  if (probe->contact_points().empty()) {
    why = "the model has no collision geometry to drop";
    return results;
  }
  // The generic checks' start: the file pose, the lowest contact point 2 cm above the floor,
  // with the joints at their initial positions (derived.X_WL has them at zero).
  double lowest = std::numeric_limits<double>::infinity();
  for (const ContactPoint& p : probe->contact_points())
    lowest = std::min(lowest, p.touching(probe->link_pose(p.link)).z());
  Eigen::Isometry3d start = as_isometry(model.root().X_PL);
  start.translation().z() += kDrop - lowest;

  mjModel* m = load_mujoco_export(
      model, derived, options.sim, sink, why, [&](const std::filesystem::path& file, std::string& reason) {
        return weld_joints(model, file, reason) && (!options.mutate_export || options.mutate_export(file, reason));
      });
  if (!m) return results;
  // As the tank cross-check and Choreonoid's MuJoCo plugin: elliptic cones, Euler at 1 ms, μ on
  // every geom (MuJoCo takes the larger of a pair). The contact bits stay as exported: the
  // floor is a default geom, which every exported collision geom must touch.
  m->opt.cone = mjCONE_ELLIPTIC;
  m->opt.integrator = mjINT_EULER;
  m->opt.timestep = kSample;
  for (int g = 0; g < m->ngeom; ++g) {
    m->geom_friction[3 * g] = options.sim.contact_params.friction;
    m->geom_condim[g] = 3;
  }
  const int floor = mj_name2id(m, mjOBJ_GEOM, "bodysim_floor");
  const double time_constant = m->geom_solref[2 * floor], damping_ratio = m->geom_solref[2 * floor + 1];
  const double dmax = m->geom_solimp[5 * floor + 1];
  DropCrossCheckReport measured;
  // MuJoCo 2.2.2's mjc_PlaneConvex: tolplanemesh = 0.3 of the mesh geom's rbound.
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] != mjGEOM_MESH || (m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0)) continue;
    const double skip = 0.3 * m->geom_rbound[g];
    measured.mesh_contact_skip_min = measured.collision_meshes ? std::min(measured.mesh_contact_skip_min, skip) : skip;
    measured.mesh_contact_skip_max = std::max(measured.mesh_contact_skip_max, skip);
    ++measured.collision_meshes;
  }
  measured.drop_height = kDrop;
  // Simbody's contact points in the root's frame (the joints are locked): where the model
  // stands, and when it came to stand there.
  std::vector<SupportPoint> points;
  const Eigen::Isometry3d root_inverse = probe->link_pose(0).inverse();
  for (const ContactPoint& p : probe->contact_points()) {
    const Eigen::Isometry3d X_RL = root_inverse * probe->link_pose(p.link);
    SupportPoint in_root = p;
    in_root.link = 0;
    in_root.position_in_link = X_RL * p.position_in_link;
    in_root.rim_axis = X_RL.linear() * p.rim_axis;
    in_root.rim_start = X_RL.linear() * p.rim_start;
    points.push_back(in_root);
  }
  try {
    measured.simbody =
        drop([&] { return std::make_unique<SimbodyEngine>(Simulation::build(model, derived, locked, quiet), start); },
             start, points);
    measured.mujoco = drop([&] { return std::make_unique<MujocoEngine>(model, m, start); }, start, points);
  } catch (...) {
    mj_deleteModel(m);
    throw;
  }
  mj_deleteModel(m);
  const DropMeasures& sb = measured.simbody;
  const DropMeasures& mj = measured.mujoco;
  // The settle time is set by the last impact, and the two contacts differ there by design:
  // the checker's stiff Hunt–Crossley points bounce, MuJoCo's soft constraint sinks and
  // creeps back (spec §6.5, §6.9). MuJoCo's creep follows from its solref alone, so MuJoCo is
  // held to Simbody's motion with MuJoCo's own contact relaxation after Simbody's impact. A
  // model that lands on its rest face has one impact, its first contact, at the free-fall
  // speed, and relaxes in height. One that lands tilted and tips onto its support has a
  // second: then one side of the support sinks in while the other rests, which turns the
  // model, so its relaxation ends in the tighter of the height band and the orientation band
  // across the support.
  measured.mujoco_time_constant = time_constant;
  if (sb.tipped && sb.support_time > 0) {
    measured.impact_time = sb.support_time;
    measured.relaxation_speed = sb.support_speed;
    measured.relaxation_band = std::min(kHeightTolerance, kOrientationTolerance * sb.support_span);
  } else {
    measured.impact_time = sb.first_contact;
    measured.relaxation_speed = std::sqrt(2 * options.sim.gravity * kDrop);
    measured.relaxation_band = kHeightTolerance;
  }
  measured.mujoco_relaxation =
      mujoco_relaxation(time_constant, damping_ratio, dmax, measured.relaxation_speed, measured.relaxation_band);
  measured.expected_settle = std::max(measured.impact_time + measured.mujoco_relaxation, sb.orientation_settle);
  if (report) *report = measured;

  // What holds at rest is compared only on a model at rest: Simbody's kinetic energy at the
  // end under G5's rest bound (1e-4 × weight × height). A model that tipped over may still roll
  // in either engine; one that landed on its rest face must rest in MuJoCo too.
  const double extent = [&] {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const SupportPoint& p : points) {
      lo = std::min(lo, p.touching(start).z());
      hi = std::max(hi, p.top(start).z());
    }
    return std::max(hi - lo, 1e-3);
  }();
  const double rest_bound = 1e-4 * derived.total_mass * options.sim.gravity * extent;
  const bool tumbled = sb.tipped;
  const char* kLines[] = {"rest height of the root", "rest orientation", "floor force ΣN at rest", "settle time"};
  auto skip_all = [&](const std::string& reason) {
    for (const char* line : kLines)
      results.push_back(skipped_check(std::string("MuJoCo vs Simbody, drop 2 cm, joints locked: ") + line, reason));
  };
  const bool simbody_rests = sb.kinetic_energy <= rest_bound, mujoco_rests = mj.kinetic_energy <= rest_bound;
  if (!simbody_rests || (tumbled && !mujoco_rests)) {
    const DropMeasures& moving = simbody_rests ? mj : sb;
    skip_all(
        fmt::format("{} does not come to rest within {:g} s (kinetic energy {:.3g} J, above the rest bound "
                    "{:.3g} J){}: it still rolls or rocks, and a rest is compared only at rest",
                    simbody_rests ? "MuJoCo" : "Simbody", kDuration, moving.kinetic_energy, rest_bound,
                    tumbled ? " after tipping over" : ""));
    return results;
  }
  // The height of the root when the model stands on its lowest contact point at rotation R
  // (Simbody's contact points, rigid while the joints are locked): the face it rests on.
  auto face_height = [&](const Eigen::Matrix3d& R) {
    double h = -std::numeric_limits<double>::infinity();
    for (const SupportPoint& p : points) h = std::max(h, -p.offset(R).z());
    return h;
  };
  // Which way is up in the model's own axes: the face it rests on and its tilt there, without
  // its yaw, which after a tumble is decided by sliding during the impacts.
  const Eigen::Vector3d up_sb = sb.rotation.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_mj = mj.rotation.transpose() * Eigen::Vector3d::UnitZ();
  // Resting on a line (a roller on its side), how far it turned about the line is decided by
  // the impacts and the rolling, as its yaw is: only the tilt along the line is the model's.
  const Eigen::Vector3d& line = sb.support_line;
  const bool on_line = tumbled && !line.isZero();
  const double tilt_apart = on_line ? std::abs(std::asin(std::clamp(up_mj.dot(line), -1.0, 1.0)) -
                                               std::asin(std::clamp(up_sb.dot(line), -1.0, 1.0)))
                                    : std::atan2(up_sb.cross(up_mj).norm(), up_sb.dot(up_mj));
  // Two rests that differ by the height band across the support differ by this much in tilt;
  // so do two that sink unevenly across it, each engine by up to its own deepest sink (MuJoCo's
  // soft contact sank a 133 kg capsule 0.73 mm at one end of its 0.51 m line and less at the
  // other: 1.2 mrad, Simbody's points 0.28 mm).
  const double uneven = std::max(mj.penetration, 0.0) + std::max(sb.penetration, 0.0);
  const double tilt_tolerance =
      std::max(kOrientationTolerance, sb.support_width > 0 ? (kHeightTolerance + uneven) / sb.support_width : 0.0);
  const bool other_face = tumbled && tilt_apart > kOtherFace;

  // Each engine sinks into the floor by its own compliance (Simbody's points 0.1 mm under four,
  // MuJoCo's soft constraint 0.2-0.8 mm by its solref and the number of contacts), which is
  // not the model's: the heights compared are the root's with the deepest point lifted onto the
  // floor, where the model's geometry puts it.
  const double mj_lifted = mj.height + mj.penetration, sb_lifted = sb.height + sb.penetration;
  const std::string sinks = fmt::format("sunk {:.3f} and {:.3f} mm", mj.penetration * 1e3, sb.penetration * 1e3);
  if (!tumbled) {
    results.push_back(compare("rest height of the root, less each engine's sink (" + sinks + ")", mj_lifted, sb_lifted,
                              kHeightTolerance, "m", fmt::format("±{:g} m", kHeightTolerance)));
  } else {
    // After a tumble each engine is held to the face it landed on: the root's height, less its
    // sink, above where it would stand on that face at its own orientation.
    results.push_back(compare(fmt::format("rest height of the root, less each engine's sink, above the face each "
                                          "engine rests on (it tipped; at {:.6f} and {:.6f} m, {})",
                                          mj.height, sb.height, sinks),
                              mj_lifted - face_height(mj.rotation), sb_lifted - face_height(sb.rotation),
                              kHeightTolerance, "m", fmt::format("±{:g} m", kHeightTolerance)));
  }
  if (!tumbled) {
    const double apart = angle_of(mj.rotation * sb.rotation.transpose());
    results.push_back(compare(
        fmt::format(
            "rest orientation, angle between the engines (turned {:.3g} and {:.3g} rad; turning {:.2g} and {:.2g} "
            "rad/s at the end; support {:.3g} m wide)",
            mj.turned, sb.turned, mj.turn_rate, sb.turn_rate, sb.support_width),
        apart, 0, tilt_tolerance, "rad",
        fmt::format("≤ {:.3g} rad (0.5 mm + both sinks across the support's width, ≥ 1e-3)", tilt_tolerance)));
  } else if (other_face) {
    results.push_back(skipped_check(
        "MuJoCo vs Simbody, drop 2 cm, joints locked: rest orientation",
        fmt::format("the model tipped over and the engines came to rest on different faces (up directions {:.3g} "
                    "rad apart in the model's axes): which face a tumble ends on is decided by the impacts; each "
                    "engine's height is compared on its own face",
                    tilt_apart)));
  } else {
    // A resting body does not turn by itself: a rest that creeps is a contact that does not
    // hold the model (MuJoCo's mesh contact on a narrow face).
    CheckResult c = compare(
        fmt::format("rest orientation: tilt between the engines, yaw left out after the tip{} (turning {:.2g} and "
                    "{:.2g} rad/s at the end, ≤ {:g}; support {:.3g} m wide)",
                    on_line ? " and the turn about the line it rests on" : "", mj.turn_rate, sb.turn_rate,
                    kRestTurnRate, sb.support_width),
        tilt_apart, 0, tilt_tolerance, "rad",
        fmt::format("≤ {:.3g} rad (0.5 mm + both sinks across the support's width, ≥ 1e-3)", tilt_tolerance));
    c.passed = c.passed && mj.turn_rate <= kRestTurnRate;
    results.push_back(c);
  }
  results.push_back(compare("floor force ΣN at rest", mj.floor_force, sb.floor_force,
                            kForceTolerance * std::abs(sb.floor_force), "N",
                            fmt::format("±{:g} %", kForceTolerance * 100)));
  if (tumbled) {
    // When a tip or tumble ends is decided by the impacts on the way, which differ by design
    // (Simbody's contact bounces, MuJoCo's sinks and creeps back; spec §6.5): MuJoCo tips
    // sooner or later. Its rest is compared instead: its height on its face, its tilt, and that
    // it no longer turns.
    results.push_back(skipped_check(
        "MuJoCo vs Simbody, drop 2 cm, joints locked: settle time",
        fmt::format("the model tipped over after its first contact ({:.3f} s; Simbody settled at {:.3f} s, MuJoCo at "
                    "{:.3f} s): when a tip ends is decided by the impacts, where the two contacts differ by design; "
                    "the rest is compared instead",
                    sb.first_contact, sb.settle_time, mj.settle_time)));
    return results;
  }
  // Landed on its rest face: MuJoCo is at rest no sooner than its contact relaxes after
  // Simbody's impact, and no later than that or than Simbody stops turning. That turning may be
  // Simbody's stiff contact rocking on its own, which MuJoCo's damped contact need not share, so
  // it bounds MuJoCo's settle only from above.
  const double expected = measured.expected_settle;
  const std::string impact = fmt::format("first contact {:.3f} s", measured.impact_time);
  const double relaxed = measured.impact_time + measured.mujoco_relaxation;
  const double low = (1 - kSettleTolerance) * relaxed;
  const double high = (1 + kSettleTolerance) * expected;
  CheckResult settle =
      compare(fmt::format("settle time within {:g} mm and {:g} rad of rest (Simbody: {} + MuJoCo's contact relaxation "
                          "{:.3f} s, or turned until {:.3f} s)",
                          kHeightTolerance * 1e3, kOrientationTolerance, impact, measured.mujoco_relaxation,
                          sb.orientation_settle),
              mj.settle_time, expected, 0, "s",
              low >= (1 - kSettleTolerance) * expected ? fmt::format("±{:g} %", kSettleTolerance * 100)
                                                       : fmt::format("{:.3f} to {:.3f} s", low, high));
  settle.passed = std::isfinite(mj.settle_time) && mj.settle_time >= low && mj.settle_time <= high;
  results.push_back(settle);
  return results;
}

std::string describe(const DropCrossCheckReport& report) {
  std::string out = fmt::format(
      "  cross-check: MuJoCo 2.2.2 on body2mjcf's export with every joint welded (elliptic cones, Euler 1 ms, "
      "default solref and solimp: contact time constant {:g} s); its lines: measured = MuJoCo, expected = "
      "Simbody\n",
      report.mujoco_time_constant);
  for (const auto& [name, d] : {std::pair<const char*, const DropMeasures&>{"Simbody", report.simbody},
                                std::pair<const char*, const DropMeasures&>{"MuJoCo", report.mujoco}})
    out += fmt::format(
        "  drop {:g} cm, joints locked, {:<7}: rests at z = {:.6f} m, turned {:.4g} rad, ΣN = {:.6g} N, settled "
        "at {:.3f} s (impact: {:.2f} mm below rest, then {:.2f} mm above), kinetic energy {:.3g} J; {} contacts, "
        "deepest {:.4f} mm ({}–{} over the last {:g} s), turning {:.2g} rad/s at the end\n",
        report.drop_height * 100, name, d.height, d.turned, d.floor_force, d.settle_time, d.impact_sink * 1e3,
        d.rebound * 1e3, d.kinetic_energy, d.contacts, d.penetration * 1e3, d.contacts_min, d.contacts_max,
        kForceWindow, d.turn_rate);
  // Which impact MuJoCo's settle is held to, and why that one.
  const DropMeasures& sb = report.simbody;
  const bool tipped = sb.tipped && sb.support_time > 0;
  const std::string impact =
      tipped ? fmt::format(
                   "Simbody tipped after its first contact at {:.3f} s; its last impact is the last of the {} "
                   "points it rests on ({:.1f} mm across) coming down at {:.3f} s",
                   sb.first_contact, sb.support_points, sb.support_span * 1e3, report.impact_time)
             : fmt::format("Simbody lands on its rest face: its impact is its first contact at {:.3f} s",
                           report.impact_time);
  const std::string band = tipped ? fmt::format("{:.3f} mm ({:g} rad across the support)", report.relaxation_band * 1e3,
                                                kOrientationTolerance)
                                  : fmt::format("{:.3f} mm", report.relaxation_band * 1e3);
  const bool turning_later = report.expected_settle > report.impact_time + report.mujoco_relaxation + 1e-12;
  out += fmt::format(
      "  MuJoCo's settle expected at {:.3f} s: {}, + MuJoCo's soft-contact relaxation {:.3f} s (from {:.3f} m/s "
      "back within {}){}{}\n",
      report.expected_settle, impact, report.mujoco_relaxation, report.relaxation_speed, band,
      turning_later
          ? fmt::format("; Simbody's own turning until {:.3f} s is later, an upper bound only", sb.orientation_settle)
          : "",
      tipped ? "; not compared: when a tip ends is decided by the impacts" : "");
  if (report.collision_meshes > 0) {
    const std::string skip =
        report.mesh_contact_skip_min == report.mesh_contact_skip_max
            ? fmt::format("{:.1f} mm", report.mesh_contact_skip_max * 1e3)
            : fmt::format("{:.1f}–{:.1f} mm", report.mesh_contact_skip_min * 1e3, report.mesh_contact_skip_max * 1e3);
    out += fmt::format(
        "  MuJoCo 2.2.2 collides a mesh with the floor at its deepest vertex and at most 2 of that vertex's hull "
        "neighbours, none closer to it than 0.3·rbound: {} here ({} collision mesh{}); a resting face narrower than "
        "that stands on one corner at one end, which changes from step to step\n",
        skip, report.collision_meshes, report.collision_meshes == 1 ? "" : "es");
  }
  return out;
}

}  // namespace bodyfmt::dynamics
