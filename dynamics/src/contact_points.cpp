#include "contact_points.h"

#include <bodyfmt/angles.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <variant>

namespace bodyfmt::dynamics {
namespace {

/// Directions spread evenly over the sphere (a Fibonacci lattice).
std::vector<Eigen::Vector3d> sphere_directions(int count) {
  std::vector<Eigen::Vector3d> out;
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1 - (2 * i + 1.0) / count;
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    out.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return out;
}

}  // namespace

Eigen::Vector3d ContactPoint::offset(const Eigen::Matrix3d& R) const {
  const Eigen::Vector3d centre = R * position_in_link;
  if (rim_axis.isZero()) return centre - Eigen::Vector3d(0, 0, radius);
  // The rim's lowest point is along the downward vertical projected onto the circle's plane;
  // a circle lying flat has none, and its points start where the link says.
  const Eigen::Vector3d axis = R * rim_axis;
  Eigen::Vector3d down = -Eigen::Vector3d::UnitZ() + axis.z() * axis;
  down = down.norm() > 1e-9 ? down.normalized() : Eigen::Vector3d(R * rim_start);
  return centre + radius * (rim_cos * down + rim_sin * axis.cross(down));
}

std::vector<ContactPoint> collect_contact_points(const Model& model, DiagnosticSink& sink) {
  GeometryAlreadyReported quiet(sink);
  std::vector<ContactPoint> out;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    // Distinct vertices in a deterministic order (meshes repeat vertices per face normal).
    std::set<std::array<double, 3>> distinct;
    for (const Shape& shape : link.shapes) {
      if (!shape.collision) continue;
      // Spheres and capsules under a uniform scale touch a plane at one exact point: their
      // lowest, found from the centre (a tessellated sphere would balance on a vertex and roll).
      const Eigen::Matrix3d L = shape.X_LS.linear();
      const double scale = L.col(0).norm();
      const bool uniform =
          (L.transpose() * L - scale * scale * Eigen::Matrix3d::Identity()).norm() < 1e-9 * scale * scale;
      if (uniform && scale > 0) {
        if (const auto* sphere = std::get_if<Sphere>(&shape.geometry)) {
          out.push_back({static_cast<LinkIndex>(i), shape.X_LS * Eigen::Vector3d::Zero(), sphere->radius * scale});
          continue;
        }
        if (const auto* capsule = std::get_if<Capsule>(&shape.geometry)) {
          for (double end : {-0.5, 0.5})
            out.push_back({static_cast<LinkIndex>(i), shape.X_LS * Eigen::Vector3d(0, end * capsule->height, 0),
                           capsule->radius * scale});
          continue;
        }
        // A cylinder touches a plane on the rims of its ends (open or closed): exactly at a
        // rim's lowest point when it lies or leans, on the whole rim when it stands. Its
        // tessellated 20-gon would rest on a flat lying on its side, where a cylinder rolls.
        if (const auto* cylinder = std::get_if<Cylinder>(&shape.geometry)) {
          const Eigen::Vector3d axis = L.col(1) / scale, start = L.col(0) / scale;
          for (double end : {-0.5, 0.5})
            for (int k = 0; k < kRimPoints; ++k) {
              ContactPoint p{static_cast<LinkIndex>(i), shape.X_LS * Eigen::Vector3d(0, end * cylinder->height, 0),
                             cylinder->radius * scale};
              p.rim_axis = axis;
              p.rim_start = start;
              p.rim_angle = 2 * kPi * k / kRimPoints;
              p.rim_cos = std::cos(p.rim_angle);
              p.rim_sin = std::sin(p.rim_angle);
              out.push_back(p);
            }
          continue;
        }
      }
      const TriangleMesh mesh = compute_shape_mesh(model, shape, quiet);
      for (const Eigen::Vector3d& v : mesh.vertices)
        if (v.allFinite()) distinct.insert({v.x(), v.y(), v.z()});
    }
    std::vector<Eigen::Vector3d> vertices;
    for (const auto& v : distinct) vertices.emplace_back(v[0], v[1], v[2]);
    if (static_cast<int>(vertices.size()) > kMaxPointsPerLink) {
      std::set<std::size_t> keep;
      for (const Eigen::Vector3d& d : sphere_directions(kMaxPointsPerLink)) {
        std::size_t best = 0;
        for (std::size_t k = 1; k < vertices.size(); ++k)
          if (vertices[k].dot(d) > vertices[best].dot(d)) best = k;
        keep.insert(best);
      }
      std::vector<Eigen::Vector3d> kept;
      for (std::size_t k : keep) kept.push_back(vertices[k]);
      vertices = std::move(kept);
    }
    for (const Eigen::Vector3d& v : vertices) out.push_back({static_cast<LinkIndex>(i), v});
  }
  return out;
}

}  // namespace bodyfmt::dynamics
