#include "simbody_contact.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <variant>

namespace bodyfmt::dynamics {

namespace {

SimTK::Vec3 vec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d to_eigen(const SimTK::Vec3& v) { return {v[0], v[1], v[2]}; }

/// Elastic foundation puts one spring at each face centroid, so a flat face needs small faces:
/// faces are split 1 → 4 at their edge midpoints until the longest edge is at most this
/// fraction of the mesh's bounding-box diagonal (at most kMaxRefinements times).
constexpr double kRefinedEdge = 0.05;
constexpr int kMaxRefinements = 5;
constexpr std::size_t kMaxFaces = 60000;
/// The floor is much stiffer than the model (composite stiffness k1·k2/(k1 + k2) ≈ the model's).
constexpr double kRigidFloor = 1e6;

/// A closed triangle mesh: vertices shared between faces (the tessellator repeats them per face
/// normal), degenerate faces dropped.
struct ClosedMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;
};

ClosedMesh weld(const TriangleMesh& mesh) {
  ClosedMesh out;
  std::map<std::array<long long, 3>, int> index;
  std::vector<int> remap(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices[i];
    const std::array<long long, 3> key{std::llround(v.x() * 1e10), std::llround(v.y() * 1e10),
                                       std::llround(v.z() * 1e10)};
    auto [it, added] = index.emplace(key, static_cast<int>(out.vertices.size()));
    if (added) out.vertices.push_back(v);
    remap[i] = it->second;
  }
  for (const auto& t : mesh.triangles) {
    const std::array<int, 3> f{remap[t[0]], remap[t[1]], remap[t[2]]};
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
    const Eigen::Vector3d n = (out.vertices[f[1]] - out.vertices[f[0]]).cross(out.vertices[f[2]] - out.vertices[f[0]]);
    if (!(n.norm() > 1e-16)) continue;
    out.faces.push_back(f);
  }
  return out;
}

double longest_edge(const ClosedMesh& m) {
  double e = 0;
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) e = std::max(e, (m.vertices[f[k]] - m.vertices[f[(k + 1) % 3]]).norm());
  return e;
}

/// One 1 → 4 midpoint subdivision; shared edges share their midpoint, so the mesh stays closed.
ClosedMesh subdivide(const ClosedMesh& m) {
  ClosedMesh out;
  out.vertices = m.vertices;
  std::map<std::pair<int, int>, int> midpoint;
  auto mid = [&](int a, int b) {
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    out.vertices.push_back(0.5 * (m.vertices[a] + m.vertices[b]));
    return midpoint[key] = static_cast<int>(out.vertices.size()) - 1;
  };
  for (const auto& f : m.faces) {
    const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
    out.faces.push_back({f[0], ab, ca});
    out.faces.push_back({ab, f[1], bc});
    out.faces.push_back({ca, bc, f[2]});
    out.faces.push_back({ab, bc, ca});
  }
  return out;
}

ClosedMesh refine(ClosedMesh m) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double target = kRefinedEdge * (hi - lo).norm();
  for (int level = 0; level < kMaxRefinements && longest_edge(m) > target && 4 * m.faces.size() <= kMaxFaces; ++level)
    m = subdivide(m);
  return m;
}

bool rigid(const Eigen::Affine3d& X) {
  const Eigen::Matrix3d L = X.linear();
  return (L.transpose() * L - Eigen::Matrix3d::Identity()).norm() < 1e-9 && L.determinant() > 0;
}

/// The belt surface velocity of pseudo tracks (spec §1.4, §2.3 Option B): Simbody hands every
/// generator the velocity of surface 2 relative to surface 1 (expressed in S1); a track's belt
/// moves its surface by dq·normalize(a_w × n_out), n_out = −Z at the floor. Adding that to the
/// relative velocity before the wrapped generator computes friction makes friction act on the
/// belt-relative slip, exactly as the point model does. Uniform over the patch: exact for the
/// flat face a floor touches.
class BeltGenerator : public SimTK::ContactForceGenerator {
 public:
  BeltGenerator(SimTK::ContactForceGenerator* inner, BeltInputs belt, const std::vector<LinkIndex>& link_of_mobod)
      : ContactForceGenerator(inner->getContactTypeId()), inner_(inner), belt_(belt), link_of_mobod_(link_of_mobod) {}

  void calcContactForce(const SimTK::State& s, const SimTK::Contact& contact, const SimTK::SpatialVec& V_S1S2,
                        SimTK::ContactForce& force) const override {
    inner_->setCompliantContactSubsystem(&getCompliantContactSubsystem());
    inner_->calcContactForce(s, contact, with_belt(s, contact, V_S1S2), force);
  }
  void calcContactPatch(const SimTK::State& s, const SimTK::Contact& contact, const SimTK::SpatialVec& V_S1S2,
                        SimTK::ContactPatch& patch) const override {
    inner_->setCompliantContactSubsystem(&getCompliantContactSubsystem());
    inner_->calcContactPatch(s, contact, with_belt(s, contact, V_S1S2), patch);
  }

 private:
  SimTK::SpatialVec with_belt(const SimTK::State& s, const SimTK::Contact& contact, SimTK::SpatialVec V) const {
    const SimTK::ContactTrackerSubsystem& tracker = getCompliantContactSubsystem().getContactTrackerSubsystem();
    const SimTK::ContactSurfaceIndex s1 = contact.getSurface1(), s2 = contact.getSurface2();
    for (const SimTK::ContactSurfaceIndex surface : {s1, s2}) {
      const SimTK::MobilizedBody& body = tracker.getMobilizedBody(surface);
      const LinkIndex link = link_of_mobod_[body.getMobilizedBodyIndex()];
      if (link < 0) continue;
      const double dq = (*belt_.track_speed)[link];
      const Eigen::Vector3d& axis = (*belt_.track_axis)[link];
      if (dq == 0 || axis.isZero()) continue;
      const SimTK::Vec3 d = (body.getBodyRotation(s) * vec3(axis)) % SimTK::Vec3(0, 0, -1);
      if (d.norm() < 1e-9) continue;
      const SimTK::Vec3 belt_G = dq * d / d.norm();
      const SimTK::Rotation R_GS1 =
          tracker.getMobilizedBody(s1).getBodyRotation(s) * tracker.getContactSurfaceTransform(s1).R();
      const SimTK::Vec3 belt_S1 = ~R_GS1 * belt_G;
      V[1] += (surface == s2 ? 1.0 : -1.0) * belt_S1;
    }
    return V;
  }

  std::unique_ptr<SimTK::ContactForceGenerator> inner_;
  BeltInputs belt_;
  const std::vector<LinkIndex>& link_of_mobod_;
};

}  // namespace

std::unique_ptr<SimbodyContact> SimbodyContact::build(SimTK::MultibodySystem& system,
                                                      SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                                                      const std::vector<SimTK::MobilizedBodyIndex>& mobod,
                                                      const ContactParams& params, double weight, BeltInputs belt,
                                                      DiagnosticSink& sink, std::vector<ContactPoint>& springs) {
  auto out = std::make_unique<SimbodyContact>();
  GeometryAlreadyReported quiet(sink);
  const std::vector<Eigen::Isometry3d> X_WL = compute_world_frames(model);

  // Every collision shape as a Brick (a Box placed rigidly) or a refined closed mesh.
  struct Brick {
    LinkIndex link;
    Eigen::Isometry3d X_LS;
    Eigen::Vector3d half;
  };
  struct Mesh {
    LinkIndex link;
    ClosedMesh mesh;
    SimTK::ContactGeometry::TriangleMesh geometry;
  };
  std::vector<Brick> bricks;
  std::vector<Mesh> meshes;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const LinkIndex link = static_cast<LinkIndex>(i);
    for (const Shape& shape : model.links[i].shapes) {
      if (!shape.collision) continue;
      if (const auto* box = std::get_if<Box>(&shape.geometry); box && rigid(shape.X_LS)) {
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = shape.X_LS.linear();
        X.translation() = shape.X_LS.translation();
        bricks.push_back({link, X, 0.5 * box->size});
        continue;
      }
      ClosedMesh mesh = weld(compute_shape_mesh(model, shape, quiet));
      if (mesh.faces.empty()) continue;  // nothing to touch (the loader reported why, if anything)
      mesh = refine(std::move(mesh));
      try {
        SimTK::Array_<SimTK::Vec3> vertices;
        SimTK::Array_<int> faces;
        for (const auto& v : mesh.vertices) vertices.push_back(vec3(v));
        for (const auto& f : mesh.faces)
          for (int k : f) faces.push_back(k);
        meshes.push_back({link, mesh, SimTK::ContactGeometry::TriangleMesh(vertices, faces)});
      } catch (const std::exception& e) {
        report_rule(sink, "dynamics-contact-geometry", shape.source,
                    fmt::format("collision shape of link \"{}\" is not a closed surface, so Simbody's TriangleMesh "
                                "refuses it ({}); with --contact simbody it does not touch the floor",
                                model.links[i].name, e.what()));
      }
    }
  }

  // Stiffness. A Brick vertex gets what a point of the point model gets, k = W/(4·d). A mesh gets
  // a pressure per depth chosen so that the model's weight on the faces that lie flat at its
  // lowest level (file pose) sinks d: k = W/(A·d); A is 1/6 of the surface area if none does.
  out->brick_stiffness_ = params.stiffness > 0 ? params.stiffness : weight / (4 * params.reference_depth);
  double lowest = std::numeric_limits<double>::infinity();
  for (const Brick& b : bricks)
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((c & 1 ? 1 : -1) * b.half.x(), (c & 2 ? 1 : -1) * b.half.y(),
                                   (c & 4 ? 1 : -1) * b.half.z());
      lowest = std::min(lowest, (X_WL[b.link] * (b.X_LS * corner)).z());
    }
  for (const Mesh& m : meshes)
    for (const auto& v : m.mesh.vertices) lowest = std::min(lowest, (X_WL[m.link] * v).z());
  double flat_area = 0, total_area = 0;
  for (const Mesh& m : meshes)
    for (const auto& f : m.mesh.faces) {
      const Eigen::Vector3d a = X_WL[m.link] * m.mesh.vertices[f[0]], b = X_WL[m.link] * m.mesh.vertices[f[1]],
                            c = X_WL[m.link] * m.mesh.vertices[f[2]];
      const double area = 0.5 * (b - a).cross(c - a).norm();
      total_area += area;
      if (std::max({a.z(), b.z(), c.z()}) <= lowest + 1e-6) flat_area += area;
    }
  const double area = flat_area > 0 ? flat_area : total_area / 6;
  out->mesh_stiffness_ = area > 0 ? weight / (area * params.reference_depth) : 0;

  // The contact subsystems, the floor and the shapes.
  out->tracker_ = new SimTK::ContactTrackerSubsystem(system);
  out->contact_ = new SimTK::CompliantContactSubsystem(system, *out->tracker_);
  out->contact_->setTransitionVelocity(params.transition_velocity);
  out->link_of_mobod_.assign(matter.getNumBodies(), -1);
  for (std::size_t i = 0; i < mobod.size(); ++i) out->link_of_mobod_[mobod[i]] = static_cast<LinkIndex>(i);
  for (auto* inner :
       std::initializer_list<SimTK::ContactForceGenerator*>{new SimTK::ContactForceGenerator::BrickHalfSpacePenalty(),
                                                            new SimTK::ContactForceGenerator::ElasticFoundation()})
    out->contact_->adoptForceGenerator(new BeltGenerator(inner, belt, out->link_of_mobod_));

  auto material = [&](double k) {
    return SimTK::ContactMaterial(k, params.dissipation, params.friction, params.friction, 0);
  };
  // HalfSpace fills x > 0 of its frame with outward normal −X; turning X to −Z makes it the
  // solid z < 0 with the outward normal +Z (spec §2.2).
  const double floor_k = kRigidFloor * std::max({out->brick_stiffness_, out->mesh_stiffness_, 1.0});
  matter.updGround().updBody().addContactSurface(
      SimTK::Transform(SimTK::Rotation(SimTK::Pi / 2, SimTK::YAxis), SimTK::Vec3(0)),
      SimTK::ContactSurface(SimTK::ContactGeometry::HalfSpace(), material(floor_k)));
  // Floor contact only, as in the point model: the model's surfaces share one clique.
  const SimTK::ContactCliqueId model_clique = SimTK::ContactSurface::createNewContactClique();
  for (const Brick& b : bricks) {
    SimTK::MobilizedBody& body = matter.updMobilizedBody(mobod[b.link]);
    SimTK::Transform X(
        SimTK::Rotation(SimTK::Mat33(b.X_LS(0, 0), b.X_LS(0, 1), b.X_LS(0, 2), b.X_LS(1, 0), b.X_LS(1, 1), b.X_LS(1, 2),
                                     b.X_LS(2, 0), b.X_LS(2, 1), b.X_LS(2, 2)),
                        true),
        vec3(b.X_LS.translation()));
    body.updBody().addContactSurface(
        X, SimTK::ContactSurface(SimTK::ContactGeometry::Brick(vec3(b.half)), material(out->brick_stiffness_))
               .joinClique(model_clique));
    for (int c = 0; c < 8; ++c)
      springs.push_back({b.link, b.X_LS * Eigen::Vector3d((c & 1 ? 1 : -1) * b.half.x(), (c & 2 ? 1 : -1) * b.half.y(),
                                                          (c & 4 ? 1 : -1) * b.half.z())});
    ++out->bricks_;
  }
  for (const Mesh& m : meshes) {
    SimTK::MobilizedBody& body = matter.updMobilizedBody(mobod[m.link]);
    body.updBody().addContactSurface(
        SimTK::Transform(), SimTK::ContactSurface(m.geometry, material(out->mesh_stiffness_)).joinClique(model_clique));
    for (int f = 0; f < m.geometry.getNumFaces(); ++f)
      springs.push_back({m.link, to_eigen(m.geometry.findCentroid(f))});
    ++out->meshes_;
    out->mesh_faces_ += m.geometry.getNumFaces();
  }
  return out;
}

Eigen::Vector3d SimbodyContact::total_force(const SimTK::State& state, LinkIndex link) const {
  const SimTK::ContactSnapshot& active = tracker_->getActiveContacts(state);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < contact_->getNumContactForces(state); ++i) {
    const SimTK::ContactForce& f = contact_->getContactForce(state, i);
    if (!active.hasContact(f.getContactId())) continue;
    const SimTK::Contact& c = active.getContactById(f.getContactId());
    const Eigen::Vector3d on2 = to_eigen(f.getForceOnSurface2()[1]);
    const LinkIndex l1 = link_of_mobod_[tracker_->getMobilizedBody(c.getSurface1()).getMobilizedBodyIndex()];
    const LinkIndex l2 = link_of_mobod_[tracker_->getMobilizedBody(c.getSurface2()).getMobilizedBodyIndex()];
    if (l2 >= 0 && (link < 0 || l2 == link)) sum += on2;
    if (l1 >= 0 && (link < 0 || l1 == link)) sum -= on2;
  }
  return sum;
}

}  // namespace bodyfmt::dynamics
