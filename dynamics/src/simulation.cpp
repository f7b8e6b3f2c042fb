#include <bodyfmt/dynamics/simulation.h>

#include "contact_points.h"
#include "simbody_contact.h"

#include <bodyfmt/inertia.h>
#include <bodyfmt/physical.h>
#include <bodyfmt/rules.h>

#include <Simbody.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>

namespace bodyfmt::dynamics {

namespace {

SimTK::Vec3 vec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d to_eigen(const SimTK::Vec3& v) { return {v[0], v[1], v[2]}; }

SimTK::Rotation rotation(const Eigen::Matrix3d& R) {
  SimTK::Mat33 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = R(i, j);
  return SimTK::Rotation(m, true);
}
Eigen::Matrix3d to_eigen(const SimTK::Rotation& R) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = R.asMat33()(i, j);
  return m;
}
SimTK::Transform transform(const Eigen::Affine3d& X) {
  return {rotation(Eigen::Matrix3d(X.linear())), vec3(Eigen::Vector3d(X.translation()))};
}

std::string matrix_text(const Eigen::Matrix3d& I) {
  return fmt::format("[{:g}, {:g}, {:g}, {:g}, {:g}, {:g}]", I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2));
}

/// The state the contact and servo forces read besides Simbody's State: commands that live
/// outside it (spec §2.3 "Policy for track commands": the integrator restarts when they change).
struct Commands {
  std::vector<double> track_speed;               // by link
  std::vector<std::optional<JointServo>> servo;  // by link
};

struct PointForce {
  std::size_t point = 0;  // index into the contact points
  Eigen::Vector3d lever;  // from the link origin to where the force acts, world axes
  Eigen::Vector3d force;  // on the link
  double depth = 0;
};

}  // namespace

struct Simulation::Impl {
  const Model* model = nullptr;
  SimOptions options;
  double stiffness = 0;
  std::vector<ContactPoint> points;
  // The points come grouped by link: each link's run of them, and how far the run reaches from
  // the link origin (|p| + radius). A link whose origin is higher touches nothing.
  struct PointRun {
    LinkIndex link;
    std::size_t begin, end;
    double reach;
  };
  std::vector<PointRun> runs;
  std::vector<Eigen::Matrix3d> inertias;
  std::vector<double> masses;               // by link, as simulated
  std::vector<Eigen::Vector3d> centres;     // of mass, link frame
  std::vector<Eigen::Vector3d> track_axis;  // link frame, unit; zero when not a track
  Commands commands;

  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  std::vector<SimTK::MobilizedBodyIndex> mobod;  // by link
  std::vector<bool> has_joint;
  std::unique_ptr<SimbodyContact> simbody_contact;  // --contact simbody
  // The state to integrate from; once the integrator has stepped, its own state is the current one.
  SimTK::State state;
  bool stepped = false;
  std::unique_ptr<SimTK::RungeKuttaMersonIntegrator> integrator;
  std::unique_ptr<SimTK::TimeStepper> stepper;
  bool running = false;
  bool initialized = false;  // the integrator was initialized once (its statistics exist)
  long long earlier_steps = 0;
  mutable long long evaluations = 0;                // force evaluations (calls of the servo force element)
  const Simulation* owner = nullptr;                // whose budget the force elements look at
  long long earlier_attempts = 0;                   // integration steps attempted before the last restart
  long long restarts = 0;                           // after the first initialization: a command changed
  mutable std::optional<WorkBudgetExceeded> spent;  // the budget ran out (thrown through Simbody)

  const SimTK::MobilizedBody& body(LinkIndex link) const { return matter.getMobilizedBody(mobod[link]); }

  /// The current state, for queries: the integrator's own after a step. Copying it out after
  /// every advance_to() was a quarter of check-tank's CPU time (a State holds every cache entry).
  const SimTK::State& current() const { return stepped ? integrator->getState() : state; }
  /// The current state, to change before (re)starting integration from it.
  SimTK::State& editable() {
    if (stepped) {
      state = integrator->getState();
      stepped = false;
    }
    return state;
  }

  /// Where contact point `p` meets the floor: the station (link frame) and its depth below z = 0.
  std::pair<SimTK::Vec3, double> touch(const SimTK::State& s, const ContactPoint& p) const {
    const SimTK::MobilizedBody& b = body(p.link);
    const SimTK::Vec3 centre = vec3(p.position_in_link);
    if (p.radius == 0) return {centre, -b.findStationLocationInGround(s, centre)[2]};
    // A sphere or a rim touches at its lowest point, a different material point as it rolls.
    const SimTK::Transform& X = b.getBodyTransform(s);
    const SimTK::Vec3 x = X.p() + vec3(p.offset(to_eigen(X.R())));
    return {b.findStationAtGroundPoint(s, x), -x[2]};
  }

  /// Forces of every contact point touching the floor, for a state realized to Velocity. The
  /// link's pose and velocity are read once per link, not once per point: Simbody's cache
  /// lookups dominated the step otherwise.
  void contact_forces(const SimTK::State& s, std::vector<PointForce>& out) const {
    out.clear();
    const ContactParams& c = options.contact_params;
    for (const PointRun& run : runs) {
      const SimTK::MobilizedBody& b = body(run.link);
      const SimTK::Transform& X = b.getBodyTransform(s);
      if (X.p()[2] > run.reach) continue;  // no point of this link is below the floor
      const SimTK::SpatialVec& V = b.getBodyVelocity(s);
      const Eigen::Matrix3d R = to_eigen(X.R());
      const Eigen::Vector3d origin = to_eigen(X.p()), omega = to_eigen(V[0]), velocity = to_eigen(V[1]);
      Eigen::Vector3d belt = Eigen::Vector3d::Zero();
      if (const double dq = commands.track_speed[run.link]; dq != 0) {
        // Belt surface velocity dq·normalize(a_w × n_out), n_out = −Z at a floor contact.
        const Eigen::Vector3d d = (R * track_axis[run.link]).cross(Eigen::Vector3d(0, 0, -1));
        if (d.norm() > 1e-9) belt = dq * d.normalized();
      }
      for (std::size_t i = run.begin; i < run.end; ++i) {
        const ContactPoint& p = points[i];
        // The touching point, from the link origin (world axes); a sphere touches at its lowest.
        // A sphere or rim whose centre is more than its radius up touches nothing: skipped
        // before the rim's trigonometry, which made check-tank 12 % slower on SimpleTank's gun.
        const Eigen::Vector3d centre = R * p.position_in_link;
        if (origin.z() + centre.z() - p.radius >= 0) continue;
        // A rim reaches radius·√(1 − a_z²) below its centre (a its axis in the world).
        if (!p.rim_axis.isZero()) {
          const double a_z = R.row(2).dot(p.rim_axis);
          if (origin.z() + centre.z() - p.radius * std::sqrt(std::max(0.0, 1 - a_z * a_z)) >= 0) continue;
        }
        const Eigen::Vector3d lever = p.radius == 0 ? centre : p.offset(R);
        const double depth = -(origin.z() + lever.z());
        if (!(depth > 0)) continue;
        const Eigen::Vector3d v = velocity + omega.cross(lever);
        // Hunt–Crossley: k·δ·(1 + c·δ̇), never pulling the body into the floor.
        const double fn = std::max(0.0, stiffness * depth * (1 + c.dissipation * -v.z()));
        Eigen::Vector3d slip(v.x() + belt.x(), v.y() + belt.y(), 0);
        const double speed = slip.norm();
        Eigen::Vector3d force(0, 0, fn);
        if (speed > 0 && fn > 0) {
          const double ratio = speed / c.transition_velocity;
          const double mu = c.friction * (ratio < 1 ? ratio * (2 - ratio) : 1.0);
          force -= mu * fn * slip / speed;
        }
        out.push_back({i, lever, force, depth});
      }
    }
  }

  double contact_potential(const SimTK::State& s) const {
    double e = 0;
    for (const PointRun& run : runs) {
      if (body(run.link).getBodyTransform(s).p()[2] > run.reach) continue;
      for (std::size_t i = run.begin; i < run.end; ++i) {
        const double depth = touch(s, points[i]).second;
        if (depth > 0) e += 0.5 * stiffness * depth * depth;
      }
    }
    return e;
  }
};

namespace {

class ContactForce : public SimTK::Force::Custom::Implementation {
 public:
  explicit ContactForce(const Simulation::Impl& impl) : impl_(impl) {}
  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>& body_forces, SimTK::Vector_<SimTK::Vec3>&,
                 SimTK::Vector&) const override {
    impl_.contact_forces(s, scratch_);
    for (const PointForce& f : scratch_) {
      // A spatial force at the link origin, world axes (what applyForceToBodyPoint adds).
      const SimTK::Vec3 F = vec3(f.force);
      body_forces[impl_.mobod[impl_.points[f.point].link]] += SimTK::SpatialVec(vec3(f.lever) % F, F);
    }
  }
  SimTK::Real calcPotentialEnergy(const SimTK::State& s) const override { return impl_.contact_potential(s); }
  bool dependsOnlyOnPositions() const override { return false; }

 private:
  const Simulation::Impl& impl_;
  mutable std::vector<PointForce> scratch_;
};

class ServoForce : public SimTK::Force::Custom::Implementation {
 public:
  explicit ServoForce(const Simulation::Impl& impl) : impl_(impl) {}
  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>&, SimTK::Vector_<SimTK::Vec3>&,
                 SimTK::Vector& mobility_forces) const override {
    const double t = s.getTime();
    // A stiff system can crawl inside one integrator step (rejected attempts): the budget is
    // looked at from here too. Simbody takes a throw here for a failed attempt and retries with
    // a smaller step, so once spent, every evaluation throws until the integrator gives up.
    if (((++impl_.evaluations & 1023) == 0 || impl_.spent) && impl_.owner) impl_.owner->check_budget();
    for (std::size_t i = 0; i < impl_.commands.servo.size(); ++i) {
      const std::optional<JointServo>& servo = impl_.commands.servo[i];
      if (!servo || !impl_.has_joint[i]) continue;
      const SimTK::MobilizedBody& b = impl_.body(static_cast<LinkIndex>(i));
      const double q_ref = servo->q_ref ? servo->q_ref(t) : 0.0;
      const double qd_ref = servo->qd_ref ? servo->qd_ref(t) : 0.0;
      const double tau =
          servo->p_gain * (q_ref - b.getOneQ(s, 0)) + servo->d_gain * (qd_ref - b.getOneU(s, 0)) + servo->torque;
      b.applyOneMobilityForce(s, 0, tau, mobility_forces);
    }
  }
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }
  bool dependsOnlyOnPositions() const override { return false; }

 private:
  const Simulation::Impl& impl_;
};

}  // namespace

Simulation::Simulation() : impl_(std::make_unique<Impl>()) {}
Simulation::~Simulation() = default;

std::unique_ptr<Simulation> Simulation::build(const Model& model, const Derived& derived, const SimOptions& options,
                                              DiagnosticSink& sink) {
  std::unique_ptr<Simulation> sim(new Simulation());
  Impl& m = *sim->impl_;
  m.model = &model;
  m.options = options;
  const std::size_t n = model.links.size();
  if (n == 0 || derived.mass.size() != n) return nullptr;

  // Mass properties: refuse what Simbody would throw on, unless asked to balance. What is
  // physical is the gate's; a link whose mass properties are not computable was reported by
  // compute_derived (derived-not-finite).
  m.inertias.resize(n);
  m.masses.resize(n);
  m.centres.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    m.inertias[i] = symmetrized_inertia(derived.mass[i].inertia);
    m.masses[i] = derived.mass[i].mass;
    m.centres[i] = derived.mass[i].center_of_mass;
  }
  PhysicalOptions gate;
  gate.balance_inertia = options.balance_inertia;
  const PhysicalVerdict verdict = assess_physical(model, derived, gate);
  for (const PhysicalFinding& f : verdict.findings) {
    const std::size_t i = static_cast<std::size_t>(f.link);
    const Link& link = model.links[i];
    if (f.defect == PhysicalDefect::kNegativeMass) {
      report_physical(
          sink, f,
          fmt::format("link \"{}\" has mass {:g} kg; Simbody cannot simulate it", link.name, derived.mass[i].mass));
      continue;
    }
    if (f.defect != PhysicalDefect::kNotPositiveDefinite && f.defect != PhysicalDefect::kTriangle) continue;
    if (verdict.links[i].negative_mass) continue;  // refused for its mass
    const PrincipalInertia& p = f.principal;
    const std::string moments = fmt::format("({:g}, {:g}, {:g})", p.moments[0], p.moments[1], p.moments[2]);
    if (!f.balanced_by_policy) {
      report_physical(
          sink, f,
          fmt::format("principal moments {} of link \"{}\" are not physical ({}); Simbody refuses them, so "
                      "nothing was simulated",
                      moments, link.name,
                      f.validity.negative_moment ? std::string("a negative moment")
                                                 : fmt::format("A + B - C = {:g} < 0", f.validity.triangle_margin)),
          (f.balanced
               ? "nearest valid inertia (link axes, about the centre of mass): " + matrix_text(*f.balanced) + "; "
               : std::string()) +
              "--balance-inertia simulates with it");
      continue;
    }
    const Eigen::Matrix3d inertia = m.inertias[i];
    m.inertias[i] = f.balanced_inertia();
    report_physical_as(
        sink, "dynamics-inertia-balanced", f,
        fmt::format("link \"{}\": inertia {} (principal moments {}) is not physical; simulated with the "
                    "balanced tensor {} (--balance-inertia, bodyfmt::balance_inertia, as body2mjcf writes it)",
                    link.name, matrix_text(inertia), moments, matrix_text(m.inertias[i])));
  }
  if (!verdict.masses_usable) return nullptr;

  // Mobilized bodies in link order (parents come first).
  m.mobod.resize(n);
  m.has_joint.assign(n, false);
  m.track_axis.assign(n, Eigen::Vector3d::Zero());
  m.commands.track_speed.assign(n, 0.0);
  m.commands.servo.assign(n, std::nullopt);
  struct Stop {
    SimTK::MobilizedBodyIndex body;
    LinkIndex link;
    double lower, upper;
  };
  std::vector<Stop> stops;
  try {
    for (std::size_t i = 0; i < n; ++i) {
      const Link& link = model.links[i];
      const MassProperties& mp = derived.mass[i];
      const SimTK::Vec3 com = vec3(mp.center_of_mass);
      const SimTK::Mat33 Ic = [&] {
        SimTK::Mat33 r;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) r(a, b) = m.inertias[i](a, b);
        return r;
      }();
      // MassProperties wants the inertia about the body origin (spec §2.1).
      const SimTK::Inertia I_origin = SimTK::Inertia(Ic).shiftFromMassCenter(-com, mp.mass);
      SimTK::Body::Rigid body(SimTK::MassProperties(mp.mass, com, I_origin));
      if (i == 0) {
        if (link.joint_type == JointType::kFree) {
          SimTK::MobilizedBody::Free root(m.matter.Ground(), SimTK::Transform(), body, SimTK::Transform());
          m.mobod[i] = root.getMobilizedBodyIndex();
        } else {
          SimTK::MobilizedBody::Weld root(m.matter.Ground(), transform(link.X_PL), body, SimTK::Transform());
          m.mobod[i] = root.getMobilizedBodyIndex();
        }
        continue;
      }
      SimTK::MobilizedBody& parent = m.matter.updMobilizedBody(m.mobod[link.parent]);
      const Eigen::Vector3d axis =
          link.joint_axis.norm() > 0 ? Eigen::Vector3d(link.joint_axis.normalized()) : Eigen::Vector3d::UnitZ();
      const bool moving =
          (link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic) && !options.lock_joints;
      if (moving) {
        // Pin turns about Z of its frames, Slider moves along X: map that axis onto the joint
        // axis on both sides so that the body frame is the link frame at q = 0.
        const SimTK::CoordinateAxis along(link.joint_type == JointType::kRevolute ? 2 : 0);
        const SimTK::Rotation R_LJ(SimTK::UnitVec3(vec3(axis)), along);
        const SimTK::Transform X_PF(rotation(Eigen::Matrix3d(link.X_PL.linear())) * R_LJ,
                                    vec3(Eigen::Vector3d(link.X_PL.translation())));
        const SimTK::Transform X_BM(R_LJ, SimTK::Vec3(0));
        if (link.joint_type == JointType::kRevolute) {
          SimTK::MobilizedBody::Pin pin(parent, X_PF, body, X_BM);
          m.mobod[i] = pin.getMobilizedBodyIndex();
        } else {
          SimTK::MobilizedBody::Slider slider(parent, X_PF, body, X_BM);
          m.mobod[i] = slider.getMobilizedBodyIndex();
        }
        m.has_joint[i] = true;
        const bool lower = link.joint_range_lower > -kUnlimited && std::isfinite(link.joint_range_lower);
        const bool upper = link.joint_range_upper < kUnlimited && std::isfinite(link.joint_range_upper);
        if (options.joint_stops && (lower || upper) && link.joint_range_lower <= link.joint_range_upper)
          stops.push_back({m.mobod[i], static_cast<LinkIndex>(i), lower ? link.joint_range_lower : -1e30,
                           upper ? link.joint_range_upper : 1e30});
        continue;
      }
      // Fixed links and pseudo tracks are welded: a track has no DOF (spec §1.1). A locked
      // joint is welded at its initial position.
      if (link.joint_type == JointType::kPseudoContinuousTrack) m.track_axis[i] = axis;
      Eigen::Affine3d X_PB = link.X_PL;
      if (link.joint_type == JointType::kRevolute)
        X_PB.rotate(Eigen::AngleAxisd(link.initial_displacement, axis));
      else if (link.joint_type == JointType::kPrismatic)
        X_PB.translate(axis * link.initial_displacement);
      SimTK::MobilizedBody::Weld weld(parent, transform(X_PB), body, SimTK::Transform());
      m.mobod[i] = weld.getMobilizedBodyIndex();
    }
  } catch (const std::exception& e) {
    report_rule(sink, "internal-error", model.source, std::string("Simbody refused the model: ") + e.what());
    return nullptr;
  }

  if (options.gravity != 0)
    SimTK::Force::Gravity(m.forces, m.matter, SimTK::UnitVec3(vec3(options.gravity_direction)), options.gravity);
  std::vector<double> q0(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) q0[i] = model.links[i].initial_displacement;
  for (const Stop& stop : stops) {
    double k = options.stop_stiffness;
    if (options.stop_frequency_limit > 0 || options.stop_frequency_floor > 0) {
      const double inertia = subtree_axis_inertia(model, derived, stop.link, q0, m.inertias);
      const double high = options.stop_frequency_limit, low = options.stop_frequency_floor;
      if (high > 0) k = std::min(k, inertia * high * high);
      if (low > 0) k = std::max(k, inertia * low * low);
    }
    SimTK::Force::MobilityLinearStop(m.forces, m.matter.updMobilizedBody(stop.body), SimTK::MobilizerQIndex(0), k,
                                     options.stop_dissipation, stop.lower, stop.upper);
  }
  if (options.contact && options.contact_model == ContactModel::kSimbody) {
    m.simbody_contact = SimbodyContact::build(m.system, m.matter, model, m.mobod, options.contact_params,
                                              std::max(derived.total_mass, 1e-3) * std::max(options.gravity, 1.0),
                                              {&m.commands.track_speed, &m.track_axis}, sink, m.points);
    m.stiffness = m.simbody_contact->brick_stiffness();
  } else if (options.contact) {
    m.points = collect_contact_points(model, sink);
    for (std::size_t first = 0; first < m.points.size();) {
      std::size_t end = first;
      double reach = 0;
      for (; end < m.points.size() && m.points[end].link == m.points[first].link; ++end)
        reach = std::max(reach, m.points[end].position_in_link.norm() + m.points[end].radius);
      // Widened so that the rounding of R·p cannot make a skipped point touch.
      m.runs.push_back({m.points[first].link, first, end, reach * (1 + 1e-9) + 1e-12});
      first = end;
    }
    m.stiffness = options.contact_params.stiffness > 0
                      ? options.contact_params.stiffness
                      : std::max(derived.total_mass, 1e-3) * std::max(options.gravity, 1.0) /
                            (4 * options.contact_params.reference_depth);
    SimTK::Force::Custom(m.forces, new ContactForce(m));
  }
  SimTK::Force::Custom(m.forces, new ServoForce(m));

  try {
    m.system.realizeTopology();
    m.state = m.system.getDefaultState();
    // The root at its file pose.
    if (model.links[0].joint_type == JointType::kFree)
      m.body(0).setQToFitTransform(m.state, transform(model.links[0].X_PL));
    for (std::size_t i = 1; i < n; ++i)
      if (m.has_joint[i] && model.links[i].initial_displacement != 0)
        m.body(static_cast<LinkIndex>(i)).setOneQ(m.state, 0, model.links[i].initial_displacement);
    m.system.realize(m.state, SimTK::Stage::Velocity);
  } catch (const std::exception& e) {
    report_rule(sink, "internal-error", model.source, std::string("Simbody refused the model: ") + e.what());
    return nullptr;
  }
  return sim;
}

const Model& Simulation::model() const { return *impl_->model; }
const std::vector<ContactPoint>& Simulation::contact_points() const { return impl_->points; }
double Simulation::contact_stiffness() const { return impl_->stiffness; }
const std::vector<Eigen::Matrix3d>& Simulation::link_inertias() const { return impl_->inertias; }

void Simulation::set_root_pose(const Eigen::Isometry3d& X_WR) {
  impl_->running = false;
  if (impl_->model->links[0].joint_type != JointType::kFree) return;
  SimTK::State& state = impl_->editable();
  impl_->body(0).setQToFitTransform(state, transform(X_WR));
  impl_->system.realize(state, SimTK::Stage::Velocity);
}

void Simulation::set_root_velocity(const Eigen::Vector3d& omega, const Eigen::Vector3d& v) {
  impl_->running = false;
  if (impl_->model->links[0].joint_type != JointType::kFree) return;
  const SimTK::MobilizedBody& root = impl_->body(0);
  SimTK::State& state = impl_->editable();
  root.setUToFitAngularVelocity(state, vec3(omega));
  root.setUToFitLinearVelocity(state, vec3(v));
  impl_->system.realize(state, SimTK::Stage::Velocity);
}

void Simulation::set_joint_position(LinkIndex link, double q) {
  impl_->running = false;
  if (!impl_->has_joint[link]) return;
  SimTK::State& state = impl_->editable();
  impl_->body(link).setOneQ(state, 0, q);
  impl_->system.realize(state, SimTK::Stage::Velocity);
}

void Simulation::set_joint_velocity(LinkIndex link, double qd) {
  impl_->running = false;
  if (!impl_->has_joint[link]) return;
  SimTK::State& state = impl_->editable();
  impl_->body(link).setOneU(state, 0, qd);
  impl_->system.realize(state, SimTK::Stage::Velocity);
}

void Simulation::set_time(double t) {
  impl_->running = false;
  impl_->editable().setTime(t);
}

void Simulation::set_track_speed(LinkIndex link, double dq) {
  impl_->running = false;
  impl_->commands.track_speed[link] = dq;
}

void Simulation::set_servo(LinkIndex link, JointServo servo) {
  impl_->running = false;
  impl_->commands.servo[link] = std::move(servo);
}

void Simulation::clear_servo(LinkIndex link) {
  impl_->running = false;
  impl_->commands.servo[link].reset();
}

void Simulation::restart() {
  Impl& m = *impl_;
  if (!m.integrator) {
    m.integrator = std::make_unique<SimTK::RungeKuttaMersonIntegrator>(m.system);
    m.integrator->setAccuracy(m.options.accuracy);
    m.stepper = std::make_unique<SimTK::TimeStepper>(m.system, *m.integrator);
  }
  // Statistics across restarts: the integrator's own counters restart with it.
  if (m.initialized) {
    m.earlier_steps += m.integrator->getNumStepsTaken();
    m.earlier_attempts += m.integrator->getNumStepsAttempted();
    m.integrator->resetAllStatistics();
    ++m.restarts;
  }
  m.stepper->initialize(m.editable());
  m.initialized = true;
  m.running = true;
}

void Simulation::advance_to(double t) {
  Impl& m = *impl_;
  if (!m.running) restart();
  if (t > m.current().getTime()) {
    // In chunks of internal steps, so that the budget is looked at while the integrator crawls.
    m.integrator->setInternalStepLimit(kBudgetChunk);
    m.owner = this;
    try {
      for (;;) {
        const SimTK::Integrator::SuccessfulStepStatus status = m.stepper->stepTo(t);
        check_budget();
        if (status != SimTK::Integrator::ReachedStepLimit) break;
      }
    } catch (const std::exception& e) {
      if (m.spent) throw WorkBudgetExceeded(*m.spent);  // Simbody may wrap what a force element threw
      // Simbody's message names no link: add the likely cause and locate it there.
      std::string message = e.what();
      const std::size_t cut = message.find_first_of("\r\n", message.find_first_not_of("\r\n "));
      message = message.substr(0, cut == std::string::npos ? 200 : std::min<std::size_t>(cut, 200));
      SourceLocation where;
      const std::string cause = stiffest_part(where);
      throw EngineFailure(fmt::format("Simbody stopped at t = {:.6g} s ({}); the likely cause: {}",
                                      m.integrator->getTime(), message, cause),
                          where);
    }
  }
  m.stepped = true;
  m.system.realize(m.current(), SimTK::Stage::Velocity);
}

void Simulation::check_budget() const {
  const Impl& m = *impl_;
  if (m.spent) throw WorkBudgetExceeded(*m.spent);
  const double simulated = m.integrator->getTime();
  const long long steps = m.earlier_attempts + (m.initialized ? m.integrator->getNumStepsAttempted() : 0);
  const double cpu = static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
  const bool steps_out = m.options.max_steps_per_second > 0 &&
                         static_cast<double>(steps) > m.options.max_steps_per_second * std::max(1.0, simulated);
  const bool cpu_out = m.options.max_cpu_seconds > 0 && cpu > m.options.max_cpu_seconds;
  if (!steps_out && !cpu_out) return;
  const std::string spent =
      steps_out
          ? fmt::format(
                "the integrator needed more than {:g} steps per simulated second ({} steps attempted to t = {:g} s; "
                "--max-steps-per-second)",
                m.options.max_steps_per_second, steps, simulated)
          : fmt::format("the simulation used more than {:g} CPU seconds (at t = {:g} s, {} steps; --max-cpu)",
                        m.options.max_cpu_seconds, simulated, steps);
  SourceLocation where = m.model->source;
  const bool by_commands = steps_out && 2 * m.restarts > steps;
  // Every change of a track speed or servo restarts the integrator: when the restarts are most
  // of the steps, the commands are the cause, not a stiff part.
  const std::string cause =
      by_commands ? fmt::format(
                        "{} of them were restarts for changed commands (each change of a track speed or a "
                        "servo restarts the integrator): the commands are denser in time than the budget",
                        m.restarts)
                  : stiffest_part(where);
  m.spent.emplace(spent + ": " + cause, where, by_commands);
  throw WorkBudgetExceeded(*m.spent);
}

std::string Simulation::stiffest_part(SourceLocation& where) const {
  // An explicit integrator's step is bounded by the fastest oscillation in the system: the
  // estimates below are the natural frequencies of each link alone on its contact springs
  // (vertical and rocking) and on its servo, in rad/s.
  const Impl& m = *impl_;
  const Model& model = *m.model;
  double fastest = 0;
  std::string why;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    const double mass = m.masses[i];
    const PrincipalInertia principal = principal_inertia(m.inertias[i]);
    const double smallest = std::min({principal.moments[0], principal.moments[1], principal.moments[2]});
    int count = 0;
    double lever_squared = 0, farthest = 0;
    for (const ContactPoint& p : m.points) {
      if (p.link != static_cast<LinkIndex>(i)) continue;
      ++count;
      // Where it touches with the link unturned: a rim point at its place on the rim.
      const double r = (p.offset(Eigen::Matrix3d::Identity()) - m.centres[i]).norm();
      lever_squared += r * r;
      farthest = std::max(farthest, r);
    }
    if (count > 0 && mass > 0) {
      const double vertical = std::sqrt(m.stiffness * count / mass);
      const double rocking = smallest > 0 ? std::sqrt(m.stiffness * lever_squared / smallest) : 0;
      const double w = std::max(vertical, rocking);
      if (w > fastest) {
        fastest = w;
        where = link.shapes.empty() ? link.source : link.shapes.front().source;
        why = fmt::format(
            "the floor contact of link \"{}\" is the stiffest part: {} contact points up to {:.3g} m from its "
            "centre of mass, {:.3g} N/m each, against {:.3g} kg and a smallest principal moment of {:.3g} kg·m², "
            "oscillate at about {:.3g} rad/s; a softer contact (--contact-depth) or the inertia of the link's "
            "shape lets it run",
            link.name, count, farthest, m.stiffness, mass, smallest, w);
      }
    }
    if (const std::optional<JointServo>& servo = m.commands.servo[i]; servo && smallest > 0) {
      const double w = std::sqrt(std::abs(servo->p_gain) / smallest);
      if (w > fastest) {
        fastest = w;
        where = source_of(link, LinkSources::kName);
        why = fmt::format(
            "the servo of link \"{}\" is the stiffest part: P = {:g} against a smallest principal moment of {:.3g} "
            "kg·m² oscillates at about {:.3g} rad/s; a lower gain lets it run",
            link.name, servo->p_gain, smallest, w);
      }
    }
  }
  if (why.empty() || fastest < 1e3) {
    double worst_ratio = 0;
    for (std::size_t i = 0; i < model.links.size(); ++i) {
      const PrincipalInertia principal = principal_inertia(m.inertias[i]);
      const double lo = std::min({principal.moments[0], principal.moments[1], principal.moments[2]});
      const double hi = std::max({principal.moments[0], principal.moments[1], principal.moments[2]});
      const double ratio = lo > 0 ? hi / lo : std::numeric_limits<double>::infinity();
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        where = inertia_source(model.links[i]);
        why = fmt::format(
            "no stiff contact or servo explains it; the most ill-conditioned inertia is link \"{}\"'s, whose "
            "principal moments differ by a factor of {:.3g}",
            model.links[i].name, ratio);
      }
    }
  }
  return why.empty() ? std::string("no cause found in the model") : why;
}

double Simulation::time() const { return impl_->current().getTime(); }

Eigen::Isometry3d Simulation::link_pose(LinkIndex link) const {
  const SimTK::Transform& X = impl_->body(link).getBodyTransform(impl_->current());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = to_eigen(X.R());
  out.translation() = to_eigen(X.p());
  return out;
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> Simulation::link_velocity(LinkIndex link) const {
  const SimTK::SpatialVec& V = impl_->body(link).getBodyVelocity(impl_->current());
  return {to_eigen(V[0]), to_eigen(V[1])};
}

double Simulation::joint_position(LinkIndex link) const {
  return impl_->has_joint[link] ? impl_->body(link).getOneQ(impl_->current(), 0) : 0.0;
}
double Simulation::joint_velocity(LinkIndex link) const {
  return impl_->has_joint[link] ? impl_->body(link).getOneU(impl_->current(), 0) : 0.0;
}
bool Simulation::has_joint(LinkIndex link) const { return impl_->has_joint[link]; }

double Simulation::total_mass() const { return impl_->matter.calcSystemMass(impl_->current()); }
Eigen::Vector3d Simulation::center_of_mass() const {
  return to_eigen(impl_->matter.calcSystemMassCenterLocationInGround(impl_->current()));
}
Eigen::Vector3d Simulation::center_of_mass_velocity() const {
  return to_eigen(impl_->matter.calcSystemMassCenterVelocityInGround(impl_->current()));
}
std::pair<Eigen::Vector3d, Eigen::Vector3d> Simulation::central_momentum() const {
  const SimTK::SpatialVec H = impl_->matter.calcSystemCentralMomentum(impl_->current());
  return {to_eigen(H[0]), to_eigen(H[1])};
}

double Simulation::kinetic_energy() const { return impl_->system.calcKineticEnergy(impl_->current()); }

double Simulation::energy() const {
  const SimTK::State& s = impl_->current();
  impl_->system.realize(s, SimTK::Stage::Dynamics);
  return impl_->system.calcEnergy(s);
}

double Simulation::mesh_stiffness() const {
  return impl_->simbody_contact ? impl_->simbody_contact->mesh_stiffness() : 0.0;
}
int Simulation::contact_bricks() const { return impl_->simbody_contact ? impl_->simbody_contact->bricks() : 0; }
int Simulation::contact_meshes() const { return impl_->simbody_contact ? impl_->simbody_contact->meshes() : 0; }
int Simulation::contact_mesh_faces() const { return impl_->simbody_contact ? impl_->simbody_contact->mesh_faces() : 0; }

Eigen::Vector3d Simulation::total_contact_force(LinkIndex link) const {
  if (impl_->simbody_contact) return impl_->simbody_contact->total_force(impl_->current(), link);
  std::vector<PointForce> forces;
  impl_->contact_forces(impl_->current(), forces);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const PointForce& f : forces)
    if (link < 0 || impl_->points[f.point].link == link) sum += f.force;
  return sum;
}

double Simulation::max_penetration(LinkIndex link) const {
  double deepest = -std::numeric_limits<double>::infinity();
  for (const ContactPoint& p : impl_->points) {
    if (link >= 0 && p.link != link) continue;
    deepest = std::max(deepest, impl_->touch(impl_->current(), p).second);
  }
  return deepest;
}

Eigen::MatrixXd Simulation::mass_matrix() const {
  SimTK::Matrix M;
  impl_->matter.calcM(impl_->current(), M);
  Eigen::MatrixXd out(M.nrow(), M.ncol());
  for (int i = 0; i < M.nrow(); ++i)
    for (int j = 0; j < M.ncol(); ++j) out(i, j) = M(i, j);
  return out;
}

int Simulation::mobility_index(LinkIndex link) const {
  if (!impl_->has_joint[link]) return -1;
  return static_cast<int>(impl_->body(link).getFirstUIndex(impl_->current()));
}

long long Simulation::force_evaluations() const { return impl_->evaluations; }

long long Simulation::steps_taken() const {
  return impl_->earlier_steps + (impl_->initialized ? impl_->integrator->getNumStepsTaken() : 0);
}

bool Simulation::finite() const {
  const SimTK::Vector& q = impl_->current().getQ();
  const SimTK::Vector& u = impl_->current().getU();
  for (int i = 0; i < q.size(); ++i)
    if (!std::isfinite(q[i])) return false;
  for (int i = 0; i < u.size(); ++i)
    if (!std::isfinite(u[i])) return false;
  return true;
}

Eigen::MatrixXd Simulation::mass_matrix_at(const std::vector<double>& q_by_link) {
  SimTK::State& state = impl_->editable();
  for (std::size_t i = 0; i < q_by_link.size() && i < impl_->has_joint.size(); ++i)
    if (impl_->has_joint[i]) impl_->body(static_cast<LinkIndex>(i)).setOneQ(state, 0, q_by_link[i]);
  impl_->running = false;
  impl_->system.realize(state, SimTK::Stage::Velocity);
  return mass_matrix();
}

}  // namespace bodyfmt::dynamics
