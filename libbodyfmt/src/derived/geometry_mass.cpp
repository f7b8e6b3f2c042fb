#include <bodyfmt/angles.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/geometry_mass.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/tessellate.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace bodyfmt {
namespace {

using Position = std::tuple<double, double, double>;

MassProperties from_moments(double volume, const Eigen::Vector3d& centroid, const Eigen::Matrix3d& inertia) {
  MassProperties m;
  m.mass = volume;
  m.center_of_mass = centroid;
  m.inertia = inertia;
  return m;
}

// Inertia about the centroid <-> second moments Σ = ∫ x xᵀ dV about it: I = tr(Σ)·1 - Σ.
Eigen::Matrix3d second_moments(const Eigen::Matrix3d& inertia) {
  return 0.5 * inertia.trace() * Eigen::Matrix3d::Identity() - inertia;
}
Eigen::Matrix3d inertia_of(const Eigen::Matrix3d& second) {
  return second.trace() * Eigen::Matrix3d::Identity() - second;
}

// A solid of revolution about Y centred at the origin: axial moment and transverse one.
MassProperties about_y(double volume, double axial, double transverse, double centroid_y = 0) {
  return from_moments(volume, Eigen::Vector3d(0, centroid_y, 0),
                      Eigen::Vector3d(transverse, axial, transverse).asDiagonal());
}

}  // namespace

MeshSolidity mesh_solidity(const TriangleMesh& mesh) {
  // Welded by exact position: a tessellated box has 24 vertices at 8 positions.
  std::map<Position, int> ids;
  std::vector<int> welded(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices[i];
    welded[i] = ids.emplace(Position{v.x(), v.y(), v.z()}, static_cast<int>(ids.size())).first->second;
  }
  // Per undirected edge: how often it is run forwards minus backwards, and how often at all.
  std::map<std::pair<int, int>, std::pair<int, int>> edges;
  const int n = static_cast<int>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= n || t[1] >= n || t[2] >= n) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = welded[static_cast<std::size_t>(t[k])], b = welded[static_cast<std::size_t>(t[(k + 1) % 3])];
      if (a == b) continue;  // a degenerate corner bounds nothing
      auto& [balance, uses] = edges[{std::min(a, b), std::max(a, b)}];
      balance += a < b ? 1 : -1;
      ++uses;
    }
  }
  MeshSolidity s;
  for (const auto& [edge, count] : edges) {
    if (count.second % 2 != 0)
      ++s.boundary_edges;
    else if (count.first != 0)
      ++s.misoriented_edges;
  }
  return s;
}

MassProperties mesh_mass_properties(const TriangleMesh& mesh) {
  // About the box centre, not the origin: a mesh placed far off would cancel digits.
  const BoundingBox box = bounding_box(mesh);
  const Eigen::Vector3d o = box.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.5 * (box.min + box.max));
  double six_volume = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   // ×24
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // ×120
  const int n = static_cast<int>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= n || t[1] >= n || t[2] >= n) continue;
    const Eigen::Vector3d a = mesh.vertices[static_cast<std::size_t>(t[0])] - o;
    const Eigen::Vector3d b = mesh.vertices[static_cast<std::size_t>(t[1])] - o;
    const Eigen::Vector3d c = mesh.vertices[static_cast<std::size_t>(t[2])] - o;
    // The tetrahedron (0, a, b, c): volume det/6, first moment det/24·(a+b+c), second moments
    // det/120·(aaᵀ + bbᵀ + ccᵀ + ssᵀ) with s = a + b + c.
    const double det = a.dot(b.cross(c));
    const Eigen::Vector3d s = a + b + c;
    six_volume += det;
    first += det * s;
    second += det * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  // An inside-out solid has every integral negated.
  const double sign = six_volume < 0 ? -1.0 : 1.0;
  const double volume = sign * six_volume / 6;
  if (!(volume > 0)) return from_moments(0, o, Eigen::Matrix3d::Zero());
  const Eigen::Vector3d centroid = sign * first / 24 / volume;
  const Eigen::Matrix3d about_centroid = sign * second / 120 - volume * centroid * centroid.transpose();
  return from_moments(volume, centroid + o, inertia_of(0.5 * (about_centroid + about_centroid.transpose())));
}

std::optional<MassProperties> primitive_mass_properties(const Geometry& geometry) {
  constexpr double pi = kPi;
  if (const auto* box = geometry_if<Box>(geometry)) {
    const Eigen::Vector3d s = box->size;
    if (!(s.minCoeff() >= 0)) return std::nullopt;
    const double v = s.prod();
    const Eigen::Vector3d sq = s.cwiseProduct(s);
    return from_moments(v, Eigen::Vector3d::Zero(),
                        Eigen::Vector3d(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()).asDiagonal() * (v / 12));
  }
  if (const auto* sphere = geometry_if<Sphere>(geometry)) {
    const double r = sphere->radius;
    if (!(r > 0)) return std::nullopt;
    const double v = 4.0 / 3.0 * pi * r * r * r;
    return about_y(v, 0.4 * v * r * r, 0.4 * v * r * r);
  }
  if (const auto* cylinder = geometry_if<Cylinder>(geometry)) {
    const double r = cylinder->radius, h = cylinder->height;
    if (!(r > 0 && h > 0) || !cylinder->top || !cylinder->bottom) return std::nullopt;
    const double v = pi * r * r * h;
    return about_y(v, v * r * r / 2, v * (3 * r * r + h * h) / 12);
  }
  if (const auto* cone = geometry_if<Cone>(geometry)) {
    const double r = cone->radius, h = cone->height;
    if (!(r > 0 && h > 0) || !cone->bottom) return std::nullopt;
    // Base at -h/2, apex at +h/2: the centroid a quarter of the height above the base.
    const double v = pi * r * r * h / 3;
    return about_y(v, 0.3 * v * r * r, v * (3 * r * r / 20 + 3 * h * h / 80), -h / 4);
  }
  if (const auto* capsule = geometry_if<Capsule>(geometry)) {
    const double r = capsule->radius, h = capsule->height;
    if (!(r > 0 && h >= 0)) return std::nullopt;
    // The cylinder and two hemispheres, each hemisphere's centroid 3r/8 from its flat face.
    const double cylinder = pi * r * r * h, ball = 4.0 / 3.0 * pi * r * r * r;
    return about_y(cylinder + ball, cylinder * r * r / 2 + 0.4 * ball * r * r,
                   cylinder * (3 * r * r + h * h) / 12 + ball * (0.4 * r * r + h * h / 4 + 3 * h * r / 8));
  }
  return std::nullopt;
}

MassProperties transform_mass_properties(const MassProperties& mass, const Eigen::Affine3d& transform) {
  const Eigen::Matrix3d A = transform.linear();
  const double scale = std::abs(A.determinant());
  const Eigen::Matrix3d second = scale * A * second_moments(mass.inertia) * A.transpose();
  return from_moments(scale * mass.mass, transform * mass.center_of_mass,
                      inertia_of(0.5 * (second + second.transpose())));
}

MassProperties at_density(const MassProperties& mass, double density) {
  return from_moments(density * mass.mass, mass.center_of_mass, density * mass.inertia);
}

std::optional<MassProperties> shape_mass_properties(const Model& model, const Shape& shape, DiagnosticSink& outer) {
  const Eigen::Affine3d X_LS(shape.X_LS);
  if (auto primitive = primitive_mass_properties(shape.geometry)) return transform_mass_properties(*primitive, X_LS);
  // The loader has reported the geometry's own problems (sizes, indices) at their keys.
  GeometryAlreadyReported sink(outer);
  const TriangleMesh local = compute_shape_local_mesh(model, shape, sink);
  const auto* resource = geometry_if<MeshResource>(shape.geometry);
  const SourceLocation at = resource && resource->uri_source.known() ? resource->uri_source : shape.source;
  if (local.empty()) return std::nullopt;  // a missing or empty mesh is reported where it is read
  const MeshSolidity solidity = mesh_solidity(local);
  if (!solidity.solid()) {
    const std::string what = resource ? fmt::format("mesh \"{}\"", resource->uri) : "shape";
    const std::string why =
        solidity.boundary_edges > 0
            ? fmt::format("not closed: {} edge{} bound{} a single triangle", solidity.boundary_edges,
                          solidity.boundary_edges == 1 ? "" : "s", solidity.boundary_edges == 1 ? "s" : "")
            : fmt::format("not consistently oriented: {} edge{} run the same way by two triangles",
                          solidity.misoriented_edges, solidity.misoriented_edges == 1 ? " is" : "s are");
    report_rule(outer, "inertia-geometry-not-solid", at,
                fmt::format("{} is {}; a shell is not a solid, so it adds nothing to the mass computed from the "
                            "geometry",
                            what, why),
                "close the surface (or give the link a collision primitive that approximates it)");
    return std::nullopt;
  }
  return transform_mass_properties(mesh_mass_properties(local), X_LS);
}

int enclosing_rigid_body(const Link& link, const Shape& shape) {
  // Frames list their parents first, so the walk up ends; a bad index ends it too.
  for (int f = shape.frame; f >= 0 && f < static_cast<int>(link.frames.size());) {
    const SceneFrame& frame = link.frames[static_cast<std::size_t>(f)];
    if (frame.rigid_body >= 0) return frame.rigid_body;
    if (frame.parent >= f) break;
    f = frame.parent;
  }
  return -1;
}

Eigen::Affine3d frame_in_link(const Link& link, int frame) {
  Eigen::Affine3d X = Eigen::Affine3d::Identity();
  for (int f = frame; f >= 0 && f < static_cast<int>(link.frames.size());) {
    const SceneFrame& node = link.frames[static_cast<std::size_t>(f)];
    X = Eigen::Affine3d(node.X_PF) * X;
    if (node.parent >= f) break;
    f = node.parent;
  }
  return X;
}

int LinkGeometryMass::solids_in_rigid_bodies() const {
  int n = 0;
  for (const RigidBodyGeometry& r : rigid_bodies) n += r.solids;
  return n;
}

LinkGeometryMass link_geometry_mass(const Model& model, const Link& link, DiagnosticSink& sink) {
  LinkGeometryMass result;
  result.from_visual = std::none_of(link.shapes.begin(), link.shapes.end(), [](const Shape& s) { return s.collision; });
  // Index 0: the shapes below no RigidBody; k + 1: those below mass contribution k.
  std::vector<std::vector<MassContribution>> parts(link.mass_contributions.size() + 1);
  std::vector<int> left_out(parts.size(), 0);
  for (const Shape& shape : link.shapes) {
    if (!(result.from_visual ? shape.visual : shape.collision)) continue;
    const int body = enclosing_rigid_body(link, shape);
    const std::size_t part =
        body >= 0 && body < static_cast<int>(link.mass_contributions.size()) ? static_cast<std::size_t>(body) + 1 : 0;
    const std::optional<MassProperties> m = shape_mass_properties(model, shape, sink);
    if (!m) {
      ++result.left_out;
      ++left_out[part];
      continue;
    }
    MassContribution c;
    c.mass = m->mass;
    c.center_of_mass = m->center_of_mass;
    c.inertia = m->inertia;
    parts[part].push_back(c);
  }
  result.solids = static_cast<int>(parts[0].size());
  if (!parts[0].empty()) result.volume = combine_mass_contributions(parts[0]);
  for (std::size_t k = 1; k < parts.size(); ++k) {
    if (parts[k].empty() && left_out[k] == 0) continue;
    RigidBodyGeometry body;
    body.contribution = k - 1;
    body.solids = static_cast<int>(parts[k].size());
    body.left_out = left_out[k];
    if (!parts[k].empty()) body.volume = combine_mass_contributions(parts[k]);
    result.rigid_bodies.push_back(body);
  }
  return result;
}

MassProperties combine_mass_contributions(const std::vector<MassContribution>& contributions) {
  MassProperties result;  // Choreonoid's defaults when nothing contributes (§6.4 rule 4)
  if (contributions.empty()) return result;
  double M = 0;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (const MassContribution& c : contributions) {
    M += c.mass;
    weighted += c.mass * c.center_of_mass;
  }
  result.mass = M;
  if (M == 0) {
    // §6.4 rule 3: a massless combination drops the individual inertias too.
    result.center_of_mass.setZero();
    result.inertia.setZero();
    return result;
  }
  const Eigen::Vector3d C = weighted / M;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (const MassContribution& c : contributions) {
    const Eigen::Vector3d d = C - c.center_of_mass;
    I += c.inertia + c.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  result.center_of_mass = C;
  result.inertia = I;
  return result;
}

std::optional<MassProperties> link_mass_from_geometry(const Link& link, const LinkGeometryMass& geometry,
                                                      double density) {
  if (geometry.no_solid()) return std::nullopt;
  std::vector<MassContribution> contributions;
  for (const MassContribution& c : link.mass_contributions)
    if (!c.from_link_keys || geometry.empty()) contributions.push_back(c);
  if (!geometry.empty()) {
    const MassProperties shapes = at_density(geometry.volume, density);
    MassContribution from_shapes;
    from_shapes.mass = shapes.mass;
    from_shapes.center_of_mass = shapes.center_of_mass;
    from_shapes.inertia = shapes.inertia;
    from_shapes.from_link_keys = true;
    contributions.push_back(from_shapes);
  }
  return combine_mass_contributions(contributions);
}

std::optional<MassProperties> geometry_at_mass(const LinkGeometryMass& geometry, double mass) {
  if (geometry.empty() || !std::isfinite(mass)) return std::nullopt;
  return at_density(geometry.volume, mass / geometry.volume.mass);
}

std::optional<GeometryAtWrittenMass> geometry_at_written_mass(const Link& link, const LinkGeometryMass& geometry) {
  GeometryAtWrittenMass result;
  std::vector<MassContribution> contributions = link.mass_contributions;
  const auto keys = std::find_if(contributions.begin(), contributions.end(),
                                 [](const MassContribution& c) { return c.from_link_keys; });
  if (keys != contributions.end()) {
    if (const std::optional<MassProperties> shaped = geometry_at_mass(geometry, keys->mass)) {
      keys->center_of_mass = shaped->center_of_mass;
      keys->inertia = shaped->inertia;
      result.link_keys = shaped;
    }
  }
  for (const RigidBodyGeometry& body : geometry.rigid_bodies) {
    MassContribution& c = contributions[body.contribution];
    // A massless RigidBody has no tensor to scale to; a body's shapes that are no solid leave it.
    if (body.empty() || !(c.mass > 0) || !std::isfinite(c.mass) || body.left_out > 0) continue;
    const int frame = [&] {
      for (std::size_t f = 0; f < link.frames.size(); ++f)
        if (link.frames[f].rigid_body == static_cast<int>(body.contribution)) return static_cast<int>(f);
      return -1;
    }();
    const Eigen::Affine3d X_LF = frame_in_link(link, frame);
    const Eigen::Matrix3d L = X_LF.linear();
    if (frame < 0 || !(std::abs(L.determinant()) > 0)) continue;
    RecomputedRigidBody recomputed;
    recomputed.contribution = body.contribution;
    recomputed.in_link = at_density(body.volume, c.mass / body.volume.mass);
    // The element's keys are read through its frame (c' = X c, I' = L I Lᵀ): written back through its inverse.
    const Eigen::Matrix3d L_inv = L.inverse();
    recomputed.as_written.mass = c.mass;
    recomputed.as_written.center_of_mass = X_LF.inverse() * recomputed.in_link.center_of_mass;
    const Eigen::Matrix3d I = L_inv * recomputed.in_link.inertia * L_inv.transpose();
    recomputed.as_written.inertia = 0.5 * (I + I.transpose());
    c.center_of_mass = recomputed.in_link.center_of_mass;
    c.inertia = recomputed.in_link.inertia;
    result.rigid_bodies.push_back(recomputed);
  }
  if (!result.link_keys && result.rigid_bodies.empty()) return std::nullopt;
  result.combined = combine_mass_contributions(contributions);
  return result;
}

}  // namespace bodyfmt
