// VRML97 Extrusion (body-format-spec §9), following Choreonoid's
// MeshGenerator::generateExtrusion: the same vertex layout (spine-major, cross-section-minor,
// closing points dropped), the same spine-aligned cross-section planes (SCP) and the same
// side/cap triangles. Deliberate differences with ExtrusionFrames::kRigid (every exported
// mesh), all where Choreonoid's result is not a proper rotation or is inside-out:
//  * the collinear-spine rotation uses a normalised axis (Choreonoid's axis has length
//    sin(angle), which only gives a rotation for spines along a coordinate axis), and a spine
//    along -Y turns by pi about +Z (Choreonoid builds -I there, a reflection);
//  * a Z axis taken over from a previous spine point is made perpendicular to the local Y;
//  * an `orientation` axis is normalised (Choreonoid uses it as written);
//  * a zero-length spine segment reuses the neighbouring direction instead of producing NaN;
//  * the result is oriented outward (see orient_outward).
// ExtrusionFrames::kChoreonoid keeps Choreonoid's own matrices and its exact collinearity test
// (the first three items), so that its vertices, and the boxes Choreonoid reports, are
// reproduced.

#include "tessellate/tessellate_internal.h"

#include <bodyfmt/angles.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

namespace bodyfmt::detail {

namespace {

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

/// The axis-angle formula cos(angle) I + (1 - cos(angle)) a a^T + sin(angle) [a]x for any
/// `a`: the rotation about `a` when |a| = 1, and what Choreonoid gets from an unnormalised
/// axis otherwise.
Eigen::Matrix3d axis_angle_formula(double angle, const Eigen::Vector3d& a) {
  Eigen::Matrix3d skew;
  skew << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  const double c = std::cos(angle);
  return c * Eigen::Matrix3d::Identity() + (1 - c) * a * a.transpose() + std::sin(angle) * skew;
}

/// Choreonoid's matrix for a collinear spine along the unit direction `y`: the formula with
/// angle = acos(y.y) and the axis a = +Y x y = (y.z, 0, -y.x) left unnormalised,
/// |a| = sin(angle). Equal to rotation_from_y() when y lies along +X, -X, +Z, -Z or +Y; -I
/// along -Y; for other directions not orthogonal (it shortens the cross-section along a).
Eigen::Matrix3d choreonoid_matrix_from_y(const Eigen::Vector3d& y) {
  return axis_angle_formula(std::acos(std::clamp(y.y(), -1.0, 1.0)), Eigen::Vector3d(y.z(), 0, -y.x()));
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

/// §9: no defaults; fewer than 2 points crash Choreonoid. Orientation and scale must have one
/// entry or one per spine point (shorter lists are read past their end by Choreonoid). An
/// empty list means the default (identity, 1), as in Choreonoid.
bool check_list_sizes(const Extrusion& extrusion, Reporter& reporter) {
  const std::size_t num_cs = extrusion.cross_section.size(), num_spine = extrusion.spine.size();
  bool ok = true;
  if (num_cs < 2 || num_spine < 2) {
    reporter.report(kRuleInvalidSize, fmt::format("Extrusion needs at least 2 cross_section points and 2 spine "
                                                  "points; it has {} and {}",
                                                  num_cs, num_spine));
    ok = false;
  }
  if (extrusion.orientation.size() > 1 && extrusion.orientation.size() != num_spine) {
    reporter.report(kRuleInvalidSize, fmt::format("Extrusion has {} orientation entries; 1 or one per spine point "
                                                  "({}) are required",
                                                  extrusion.orientation.size(), num_spine));
    ok = false;
  }
  if (extrusion.scale.size() > 1 && extrusion.scale.size() != num_spine) {
    reporter.report(kRuleInvalidSize, fmt::format("Extrusion has {} scale entries; 1 or one per spine point ({}) "
                                                  "are required",
                                                  extrusion.scale.size(), num_spine));
    ok = false;
  }
  return ok;
}

/// Point counts once a closing point (first == last) is dropped; the indices wrap instead.
struct Layout {
  bool spine_closed = false;
  bool cs_closed = false;
  int ns = 0;  ///< distinct spine points
  int nc = 0;  ///< distinct cross-section points
};

std::optional<Layout> layout_of(const Extrusion& extrusion, Reporter& reporter) {
  Layout l;
  l.spine_closed = extrusion.spine.front() == extrusion.spine.back();
  l.cs_closed = extrusion.cross_section.front() == extrusion.cross_section.back();
  l.ns = static_cast<int>(extrusion.spine.size()) - (l.spine_closed ? 1 : 0);
  l.nc = static_cast<int>(extrusion.cross_section.size()) - (l.cs_closed ? 1 : 0);
  if (l.ns < 2 || l.nc < 2) {
    reporter.report(kRuleDegenerate, fmt::format("Extrusion {} has fewer than 2 distinct points once its closing "
                                                 "point is removed",
                                                 l.ns < 2 ? "spine" : "cross_section"));
    return std::nullopt;
  }
  return l;
}

/// The spine-aligned cross-section planes' raw axes (VRML97 §6.18): Y along the spine tangent,
/// Z perpendicular to the two adjacent segments. Indices follow Choreonoid, including its
/// open-end conventions. `defined_z` is the first point with a Z of its own (-1: none).
struct SpineAxes {
  std::vector<Eigen::Vector3d> y;
  std::vector<Eigen::Vector3d> z;
  int defined_z = -1;
};

SpineAxes spine_axes(const std::vector<Eigen::Vector3d>& spine, const Layout& l, ExtrusionFrames frames) {
  const int ns = l.ns;
  auto S = [&](int k) -> const Eigen::Vector3d& { return spine[static_cast<std::size_t>(k)]; };
  SpineAxes axes;
  axes.y.resize(static_cast<std::size_t>(ns));
  axes.z.assign(static_cast<std::size_t>(ns), Eigen::Vector3d::Zero());
  if (ns <= 2) {
    axes.y[0] = axes.y[1] = S(1) - S(0);
    return axes;
  }
  Eigen::Vector3d previous_z = Eigen::Vector3d::Zero();
  for (int i = 0; i < ns; ++i) {
    int prev, cur, next;
    Eigen::Vector3d y;
    if (i == 0 && !l.spine_closed) {
      prev = 0, cur = 1, next = 2;
      y = S(1) - S(0);
    } else if (i == ns - 1 && !l.spine_closed) {
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
    const double tolerance = frames == ExtrusionFrames::kChoreonoid ? 0.0 : 1e-12 * a.norm() * b.norm();
    if (z.norm() <= tolerance) {
      z = axes.defined_z != -1 ? previous_z : Eigen::Vector3d::Zero();
    } else {
      if (axes.defined_z == -1) axes.defined_z = i;
      previous_z = z;
    }
    axes.y[static_cast<std::size_t>(i)] = y;
    axes.z[static_cast<std::size_t>(i)] = z;
  }
  return axes;
}

/// Zero-length tangents (repeated spine points) take the nearest defined direction. False
/// when every spine point coincides.
bool fill_zero_tangents(std::vector<Eigen::Vector3d>& y_axes) {
  const auto first = std::find_if(y_axes.begin(), y_axes.end(), [](const Eigen::Vector3d& y) { return y.norm() > 0; });
  if (first == y_axes.end()) return false;
  Eigen::Vector3d last = *first;
  for (auto& y : y_axes) {
    if (y.norm() > 0) {
      last = y;
    } else {
      y = last;
    }
  }
  return true;
}

/// The rotation of cross-section `i`: its SCP, or the collinear-spine rotation where no Z is
/// defined. Updates `axes.z[i]` as Choreonoid does (inherited, then kept from flipping).
/// With kChoreonoid, Choreonoid's matrices (see ExtrusionFrames) where they differ.
Eigen::Matrix3d section_rotation(SpineAxes& axes, int i, ExtrusionFrames frames) {
  const bool as_choreonoid = frames == ExtrusionFrames::kChoreonoid;
  const std::size_t ui = static_cast<std::size_t>(i);
  const Eigen::Vector3d y = axes.y[ui].normalized();
  if (axes.defined_z != -1) {
    if (i < axes.defined_z) axes.z[ui] = axes.z[static_cast<std::size_t>(axes.defined_z)];
    // Keep Z from flipping between neighbours (Choreonoid does the same).
    if (i > 0 && axes.z[ui].dot(axes.z[ui - 1]) < 0) axes.z[ui] = -axes.z[ui];
    Eigen::Vector3d z = as_choreonoid ? axes.z[ui] : Eigen::Vector3d(axes.z[ui] - axes.z[ui].dot(y) * y);
    if (z.norm() > 1e-12 * axes.z[ui].norm()) {
      z.normalize();
      Eigen::Matrix3d scp;
      scp.col(0) = y.cross(z);
      scp.col(1) = y;
      scp.col(2) = z;
      return scp;
    }
  }
  return as_choreonoid ? choreonoid_matrix_from_y(y) : rotation_from_y(y);
}

/// The orientation entry of cross-section `i` (identity when absent). kRigid: the rotation
/// about the normalised axis (a zero axis reads as +Z). kChoreonoid: the axis-angle formula
/// with the axis as written, as Choreonoid evaluates it (not a rotation unless |axis| = 1).
Eigen::Matrix3d section_orientation(const Extrusion& extrusion, std::size_t i, ExtrusionFrames frames) {
  const std::size_t n = extrusion.orientation.size();
  if (n == 0) return Eigen::Matrix3d::Identity();
  const Eigen::AngleAxisd& o = extrusion.orientation[n == 1 ? 0 : i];
  if (frames == ExtrusionFrames::kChoreonoid) return axis_angle_formula(o.angle(), o.axis());
  const double axis_norm = o.axis().norm();
  const Eigen::Vector3d axis = axis_norm > 0 ? Eigen::Vector3d(o.axis() / axis_norm) : Eigen::Vector3d::UnitZ();
  return Eigen::AngleAxisd(o.angle(), axis).toRotationMatrix();
}

Eigen::Vector2d section_scale(const Extrusion& extrusion, std::size_t i) {
  const std::size_t n = extrusion.scale.size();
  if (n == 0) return Eigen::Vector2d(1, 1);
  return extrusion.scale[n == 1 ? 0 : i];
}

/// Spine-major, cross-section-minor vertices, as Choreonoid lays them out.
void add_vertices(const Extrusion& extrusion, const Layout& l, SpineAxes& axes, ExtrusionFrames frames,
                  TriangleMesh& mesh) {
  mesh.vertices.reserve(static_cast<std::size_t>(l.ns) * static_cast<std::size_t>(l.nc));
  for (int i = 0; i < l.ns; ++i) {
    const std::size_t ui = static_cast<std::size_t>(i);
    const Eigen::Matrix3d m = section_rotation(axes, i, frames) * section_orientation(extrusion, ui, frames);
    const Eigen::Vector2d scale = section_scale(extrusion, ui);
    for (int j = 0; j < l.nc; ++j) {
      const Eigen::Vector2d& c = extrusion.cross_section[static_cast<std::size_t>(j)];
      mesh.vertices.push_back(m * Eigen::Vector3d(c.x() * scale.x(), 0, c.y() * scale.y()) + extrusion.spine[ui]);
    }
  }
}

void add_sides(const Layout& l, TriangleMesh& mesh) {
  const int spine_segments = l.spine_closed ? l.ns : l.ns - 1;
  const int cs_segments = l.cs_closed ? l.nc : l.nc - 1;
  mesh.triangles.reserve(static_cast<std::size_t>(2 * spine_segments) * static_cast<std::size_t>(cs_segments) +
                         static_cast<std::size_t>(2 * l.nc));
  for (int i = 0; i < spine_segments; ++i) {
    const int upper = i * l.nc, lower = ((i + 1) % l.ns) * l.nc;
    for (int j = 0; j < cs_segments; ++j) {
      const int jj = (j + 1) % l.nc;
      mesh.triangles.push_back({j + upper, j + lower, jj + lower});
      mesh.triangles.push_back({j + upper, jj + lower, jj + upper});
    }
  }
}

/// Caps: only on an open spine. A cap that collapses (scale 0 at an end, a common way to make
/// a point) is simply omitted: it has no area to cover.
void add_caps(const Extrusion& extrusion, const Layout& l, TriangleMesh& mesh, Reporter& reporter) {
  if (l.spine_closed) return;
  std::vector<int> polygon(static_cast<std::size_t>(l.nc));
  bool over_budget = false;
  if (extrusion.begin_cap) {
    for (int j = 0; j < l.nc; ++j) polygon[static_cast<std::size_t>(j)] = j;
    triangulate_polygon(mesh.vertices, polygon, mesh.triangles, &over_budget);
  }
  if (extrusion.end_cap && !over_budget) {
    const int base = l.nc * (l.ns - 1);
    for (int j = 0; j < l.nc; ++j) polygon[static_cast<std::size_t>(j)] = base + l.nc - 1 - j;
    triangulate_polygon(mesh.vertices, polygon, mesh.triangles, &over_budget);
  }
  if (over_budget)
    reporter.report(kRuleDegenerate, fmt::format("Extrusion cross_section ({} points) crosses itself too often to be "
                                                 "triangulated within the tessellation budget; its caps are left out",
                                                 l.nc));
}

/// Outward orientation. For a closed solid the signed volume decides, which covers every
/// combination of cross-section direction, negative scale and spine shape. For an open
/// surface, Choreonoid's winding faces outward when the cross-section runs counter-clockwise
/// in (x, z) with a positive scale; the SCP and orientation are rotations and do not change
/// that.
void orient_outward(const Extrusion& extrusion, const Layout& l, TriangleMesh& mesh) {
  const bool solid = l.cs_closed && (l.spine_closed || (extrusion.begin_cap && extrusion.end_cap));
  bool flip = false;
  if (solid) {
    flip = signed_volume(mesh) < 0;
  } else {
    const Eigen::Vector2d s = section_scale(extrusion, 0);
    flip = cross_section_area2(extrusion.cross_section) * s.x() * s.y() < 0;
  }
  if (flip) flip_triangles(mesh);
}

}  // namespace

TriangleMesh tessellate_extrusion(const Extrusion& extrusion, ExtrusionFrames frames, Reporter& reporter) {
  if (!check_list_sizes(extrusion, reporter)) return {};
  const std::optional<Layout> layout = layout_of(extrusion, reporter);
  if (!layout) return {};
  SpineAxes axes = spine_axes(extrusion.spine, *layout, frames);
  if (!fill_zero_tangents(axes.y)) {
    reporter.report(kRuleDegenerate, "Extrusion spine points all coincide");
    return {};
  }
  TriangleMesh mesh;
  add_vertices(extrusion, *layout, axes, frames, mesh);
  add_sides(*layout, mesh);
  add_caps(extrusion, *layout, mesh, reporter);
  orient_outward(extrusion, *layout, mesh);
  return mesh;
}

}  // namespace bodyfmt::detail
