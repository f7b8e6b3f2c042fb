// VRML97 Extrusion (body-format-spec §9), following Choreonoid's
// MeshGenerator::generateExtrusion: the same vertex layout (spine-major, cross-section-minor,
// closing points dropped), the same spine-aligned cross-section planes (SCP) and the same
// side/cap triangles. Deliberate differences, all where Choreonoid's result is not a proper
// rotation or is inside-out:
//  * the collinear-spine rotation uses a normalised axis (Choreonoid's axis has length
//    sin(angle), which only gives a rotation for spines along a coordinate axis), and a spine
//    along -Y turns by pi about +Z (Choreonoid builds -I there, a reflection);
//  * a Z axis taken over from a previous spine point is made perpendicular to the local Y;
//  * a zero-length spine segment reuses the neighbouring direction instead of producing NaN;
//  * the result is oriented outward (see orient_outward).

#include "derived/tessellate_internal.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace bodyfmt::detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The VRML97 rotation that takes +Y onto the spine direction `y` (unit), used when the
/// whole spine is collinear.
Eigen::Matrix3d rotation_from_y(const Eigen::Vector3d& y) {
  const Eigen::Vector3d axis = Eigen::Vector3d::UnitY().cross(y);  // (y.z, 0, -y.x)
  const double s = axis.norm();
  if (s > 1e-12) {
    const double angle = std::atan2(s, y.y());
    return Eigen::AngleAxisd(angle, axis / s).toRotationMatrix();
  }
  if (y.y() > 0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// Twice the signed area of the cross-section in (x, z) coordinates. Positive (counter-
/// clockwise with x right and z up) is the orientation for which Choreonoid's triangles face
/// outward.
double cross_section_area2(const std::vector<Eigen::Vector2d>& cs) {
  double area2 = 0;
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const Eigen::Vector2d& a = cs[k];
    const Eigen::Vector2d& b = cs[(k + 1) % cs.size()];
    area2 += a.x() * b.y() - b.x() * a.y();
  }
  return area2;
}

}  // namespace

TriangleMesh tessellate_extrusion(const Extrusion& extrusion, Reporter& reporter) {
  const std::vector<Eigen::Vector2d>& cs = extrusion.cross_section;
  const std::vector<Eigen::Vector3d>& spine = extrusion.spine;

  // §9: no defaults; fewer than 2 points crash Choreonoid. Orientation and scale must have
  // one entry or one per spine point (shorter lists are read past their end by Choreonoid).
  // An empty list means the default (identity, 1), as in Choreonoid.
  bool ok = true;
  if (cs.size() < 2 || spine.size() < 2) {
    reporter.report(kRuleInvalidSize,
                   fmt::format("Extrusion needs at least 2 cross_section points and 2 spine "
                               "points; it has {} and {}",
                               cs.size(), spine.size()));
    ok = false;
  }
  const std::size_t num_given = spine.size();
  if (extrusion.orientation.size() > 1 && extrusion.orientation.size() != num_given) {
    reporter.report(kRuleInvalidSize,
                   fmt::format("Extrusion has {} orientation entries; 1 or one per spine point "
                               "({}) are required",
                               extrusion.orientation.size(), num_given));
    ok = false;
  }
  if (extrusion.scale.size() > 1 && extrusion.scale.size() != num_given) {
    reporter.report(kRuleInvalidSize,
                   fmt::format("Extrusion has {} scale entries; 1 or one per spine point ({}) "
                               "are required",
                               extrusion.scale.size(), num_given));
    ok = false;
  }
  if (!ok) return {};

  // A first == last point closes the spine / cross-section; the closing point is dropped and
  // the indices wrap around instead.
  const bool spine_closed = spine.front() == spine.back();
  const bool cs_closed = cs.front() == cs.back();
  const int ns = static_cast<int>(spine.size()) - (spine_closed ? 1 : 0);
  const int nc = static_cast<int>(cs.size()) - (cs_closed ? 1 : 0);
  if (ns < 2 || nc < 2) {
    reporter.report(kRuleDegenerate,
                   fmt::format("Extrusion {} has fewer than 2 distinct points once its closing "
                               "point is removed",
                               ns < 2 ? "spine" : "cross_section"));
    return {};
  }
  auto S = [&](int k) -> const Eigen::Vector3d& { return spine[static_cast<std::size_t>(k)]; };

  // SCP axes (VRML97 §6.18): Y along the spine tangent, Z perpendicular to the two adjacent
  // segments. Indices follow Choreonoid, including its open-end conventions.
  std::vector<Eigen::Vector3d> y_axes(static_cast<std::size_t>(ns));
  std::vector<Eigen::Vector3d> z_axes(static_cast<std::size_t>(ns), Eigen::Vector3d::Zero());
  int defined_z = -1;
  if (ns > 2) {
    Eigen::Vector3d previous_z = Eigen::Vector3d::Zero();
    for (int i = 0; i < ns; ++i) {
      int prev, cur, next;
      Eigen::Vector3d y;
      if (i == 0 && !spine_closed) {
        prev = 0, cur = 1, next = 2;
        y = S(1) - S(0);
      } else if (i == ns - 1 && !spine_closed) {
        prev = ns - 3, cur = ns - 2, next = ns - 1;
        y = S(ns - 1) - S(ns - 2);
      } else {
        prev = (i + ns - 1) % ns, cur = i, next = (i + 1) % ns;
        y = S(next) - S(prev);
      }
      const Eigen::Vector3d a = S(next) - S(cur), b = S(prev) - S(cur);
      Eigen::Vector3d z = a.cross(b);
      // Collinear points: VRML97 takes the previous Z. A relative tolerance instead of
      // Choreonoid's exact zero test keeps rounding noise from defining a random Z.
      if (z.norm() <= 1e-12 * a.norm() * b.norm()) {
        z = defined_z != -1 ? previous_z : Eigen::Vector3d::Zero();
      } else {
        if (defined_z == -1) defined_z = i;
        previous_z = z;
      }
      y_axes[static_cast<std::size_t>(i)] = y;
      z_axes[static_cast<std::size_t>(i)] = z;
    }
  } else {
    y_axes[0] = y_axes[1] = S(1) - S(0);
  }

  // Zero-length tangents (repeated spine points) take the nearest defined direction.
  {
    int first_defined = -1;
    for (int i = 0; i < ns; ++i) {
      if (y_axes[static_cast<std::size_t>(i)].norm() > 0) {
        first_defined = i;
        break;
      }
    }
    if (first_defined == -1) {
      reporter.report(kRuleDegenerate, "Extrusion spine points all coincide");
      return {};
    }
    Eigen::Vector3d last = y_axes[static_cast<std::size_t>(first_defined)];
    for (auto& y : y_axes) {
      if (y.norm() > 0) {
        last = y;
      } else {
        y = last;
      }
    }
  }

  const std::size_t num_scales = extrusion.scale.size();
  const std::size_t num_orientations = extrusion.orientation.size();

  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(ns) * static_cast<std::size_t>(nc));
  for (int i = 0; i < ns; ++i) {
    const std::size_t ui = static_cast<std::size_t>(i);
    const Eigen::Vector3d y = y_axes[ui].normalized();
    Eigen::Matrix3d scp;
    bool have_scp = false;
    if (defined_z != -1) {
      if (i < defined_z) z_axes[ui] = z_axes[static_cast<std::size_t>(defined_z)];
      // Keep Z from flipping between neighbours (Choreonoid does the same).
      if (i > 0 && z_axes[ui].dot(z_axes[ui - 1]) < 0) z_axes[ui] = -z_axes[ui];
      Eigen::Vector3d z = z_axes[ui] - z_axes[ui].dot(y) * y;
      if (z.norm() > 1e-12 * z_axes[ui].norm()) {
        z.normalize();
        scp.col(0) = y.cross(z);
        scp.col(1) = y;
        scp.col(2) = z;
        have_scp = true;
      }
    }
    if (!have_scp) scp = rotation_from_y(y);

    Eigen::Vector2d scale(1, 1);
    if (num_scales == 1) scale = extrusion.scale[0];
    if (num_scales > 1) scale = extrusion.scale[ui];
    Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
    if (num_orientations > 0) {
      const Eigen::AngleAxisd& o = extrusion.orientation[num_orientations == 1 ? 0 : ui];
      const double axis_norm = o.axis().norm();
      if (axis_norm > 0) orientation = Eigen::AngleAxisd(o.angle(), o.axis() / axis_norm).toRotationMatrix();
    }
    const Eigen::Matrix3d m = scp * orientation;
    for (int j = 0; j < nc; ++j) {
      const Eigen::Vector2d& c = cs[static_cast<std::size_t>(j)];
      mesh.vertices.push_back(m * Eigen::Vector3d(c.x() * scale.x(), 0, c.y() * scale.y()) + S(i));
    }
  }

  const int spine_segments = spine_closed ? ns : ns - 1;
  const int cs_segments = cs_closed ? nc : nc - 1;
  mesh.triangles.reserve(static_cast<std::size_t>(2 * spine_segments) *
                             static_cast<std::size_t>(cs_segments) +
                         static_cast<std::size_t>(2 * nc));
  for (int i = 0; i < spine_segments; ++i) {
    const int upper = i * nc, lower = ((i + 1) % ns) * nc;
    for (int j = 0; j < cs_segments; ++j) {
      const int jj = (j + 1) % nc;
      mesh.triangles.push_back({j + upper, j + lower, jj + lower});
      mesh.triangles.push_back({j + upper, jj + lower, jj + upper});
    }
  }

  // Caps: only on an open spine. A cap that collapses (scale 0 at an end, a common way to
  // make a point) is simply omitted: it has no area to cover.
  if (!spine_closed) {
    std::vector<int> polygon(static_cast<std::size_t>(nc));
    if (extrusion.begin_cap) {
      for (int j = 0; j < nc; ++j) polygon[static_cast<std::size_t>(j)] = j;
      triangulate_polygon(mesh.vertices, polygon, mesh.triangles);
    }
    if (extrusion.end_cap) {
      const int base = nc * (ns - 1);
      for (int j = 0; j < nc; ++j) polygon[static_cast<std::size_t>(j)] = base + nc - 1 - j;
      triangulate_polygon(mesh.vertices, polygon, mesh.triangles);
    }
  }

  // Outward orientation. For a closed solid the signed volume decides, which covers every
  // combination of cross-section direction, negative scale and spine shape. For an open
  // surface, Choreonoid's winding faces outward when the cross-section runs counter-clockwise
  // in (x, z) with a positive scale; the SCP and orientation are rotations and do not change
  // that.
  const bool solid = cs_closed && (spine_closed || (extrusion.begin_cap && extrusion.end_cap));
  bool flip = false;
  if (solid) {
    flip = signed_volume(mesh) < 0;
  } else {
    const Eigen::Vector2d s = num_scales > 0 ? extrusion.scale[0] : Eigen::Vector2d(1, 1);
    flip = cross_section_area2(cs) * s.x() * s.y() < 0;
  }
  if (flip) flip_triangles(mesh);
  return mesh;
}

}  // namespace bodyfmt::detail
