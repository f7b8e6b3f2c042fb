// Geometry -> TriangleMesh (body-format-spec §9). Primitives follow Choreonoid's
// MeshGenerator vertex by vertex (src/Util/MeshGenerator.cpp) so that exported meshes match
// what Choreonoid shows; validation follows the loader's rules in §9 and §13.

#include "tessellate/tessellate_internal.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace bodyfmt {

namespace detail {

Reporter::~Reporter() {
  if (suppressed_ > 0) {
    report_rule(sink_, "geometry-more-problems", where_,
                fmt::format("{} more geometry problem(s) of this shape not reported (the first: {})", suppressed_,
                            first_suppressed_));
  }
}

void Reporter::report(const char* rule_id, std::string message) {
  if (reported_ >= kMaxReports) {
    if (suppressed_++ == 0) first_suppressed_ = rule_id;
    return;
  }
  ++reported_;
  report_rule(sink_, rule_id, where_, std::move(message));
}

void flip_triangles(TriangleMesh& mesh) {
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
}

/// tessellate() with both choices (defined below, after the shape generators).
TriangleMesh tessellate_with(const Geometry& geometry, int division_number, DiagnosticSink& sink,
                             const SourceLocation& where, TexCoords tex_coords, ExtrusionFrames frames);

}  // namespace detail

TriangleMesh tessellate(const Geometry& geometry, int division_number, DiagnosticSink& sink,
                        const SourceLocation& where, TexCoords tex_coords) {
  return detail::tessellate_with(geometry, division_number, sink, where, tex_coords, ExtrusionFrames::kRigid);
}

TriangleMesh tessellate(const Geometry& geometry, int division_number, DiagnosticSink& sink,
                        const SourceLocation& where, ExtrusionFrames frames) {
  return detail::tessellate_with(geometry, division_number, sink, where, TexCoords::kNone, frames);
}

namespace {

using detail::kRuleDegenerate;
using detail::kRuleIndexOutOfRange;
using detail::kRuleInvalidSize;
using detail::Reporter;

bool positive(double x) { return std::isfinite(x) && x > 0; }
bool non_negative(double x) { return std::isfinite(x) && x >= 0; }

void add(TriangleMesh& mesh, int a, int b, int c) { mesh.triangles.push_back({a, b, c}); }

// MeshGenerator::generateBox: 8 corners, 12 triangles.
TriangleMesh box_mesh(const Box& box, Reporter& reporter) {
  const Eigen::Vector3d& s = box.size;
  if (!non_negative(s.x()) || !non_negative(s.y()) || !non_negative(s.z())) {
    // §9: negative -> "A box cannot be generated with the given parameters"; zero is allowed.
    reporter.report(kRuleInvalidSize,
                    fmt::format("Box size ({}, {}, {}) has a negative or non-finite component", s.x(), s.y(), s.z()));
    return {};
  }
  const double x = s.x() / 2, y = s.y() / 2, z = s.z() / 2;
  TriangleMesh mesh;
  mesh.vertices = {{x, y, z}, {-x, y, z}, {-x, -y, z}, {x, -y, z}, {x, y, -z}, {-x, y, -z}, {-x, -y, -z}, {x, -y, -z}};
  static constexpr int kTriangles[12][3] = {{0, 1, 2}, {2, 3, 0}, {0, 5, 1}, {0, 4, 5}, {1, 5, 6}, {1, 6, 2},
                                            {2, 6, 7}, {2, 7, 3}, {3, 7, 4}, {3, 4, 0}, {4, 6, 5}, {4, 7, 6}};
  for (const auto& t : kTriangles) add(mesh, t[0], t[1], t[2]);
  return mesh;
}

// MeshGenerator::generateSphere: n longitudes, n/2 latitude bands, poles as single vertices.
TriangleMesh sphere_mesh(const Sphere& sphere, int n, Reporter& reporter) {
  const double r = sphere.radius;
  if (!positive(r)) {
    reporter.report(kRuleInvalidSize, fmt::format("Sphere radius {} is not positive", r));
    return {};
  }
  const int vdn = n / 2;  // latitude bands
  const int hdn = n;      // longitudes
  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>((vdn - 1) * hdn + 2));
  for (int i = 1; i < vdn; ++i) {
    const double tv = i * kPi / vdn;
    for (int j = 0; j < hdn; ++j) {
      const double th = j * 2.0 * kPi / hdn;
      mesh.vertices.emplace_back(r * std::sin(tv) * std::cos(th), r * std::cos(tv), r * std::sin(tv) * std::sin(th));
    }
  }
  const int top = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0, r, 0);
  const int bottom = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0, -r, 0);

  mesh.triangles.reserve(static_cast<std::size_t>(2 * vdn * hdn));
  for (int i = 0; i < hdn; ++i) add(mesh, top, (i + 1) % hdn, i);
  for (int i = 0; i < vdn - 2; ++i) {
    const int upper = i * hdn, lower = (i + 1) * hdn;
    for (int j = 0; j < hdn; ++j) {
      const int k = (j + 1) % hdn;
      add(mesh, j + upper, k + lower, j + lower);
      add(mesh, j + upper, k + upper, k + lower);
    }
  }
  const int offset = (vdn - 2) * hdn;
  for (int i = 0; i < hdn; ++i) add(mesh, bottom, i + offset, (i + 1) % hdn + offset);
  return mesh;
}

// MeshGenerator::generateCylinder: top ring, bottom ring, then the two cap centres.
TriangleMesh cylinder_mesh(const Cylinder& cylinder, int n, Reporter& reporter) {
  const double r = cylinder.radius, h = cylinder.height;
  if (!positive(r) || !positive(h)) {
    reporter.report(kRuleInvalidSize, fmt::format("Cylinder radius {} and height {} must both be positive", r, h));
    return {};
  }
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(2 * n));
  const double y = h / 2;
  for (int i = 0; i < n; ++i) {
    const double angle = i * 2.0 * kPi / n;
    const double x = r * std::cos(angle), z = r * std::sin(angle);
    mesh.vertices[static_cast<std::size_t>(i)] = {x, y, z};
    mesh.vertices[static_cast<std::size_t>(i + n)] = {x, -y, z};
  }
  const int top_center = 2 * n, bottom_center = 2 * n + 1;
  mesh.vertices.emplace_back(0, y, 0);
  mesh.vertices.emplace_back(0, -y, 0);
  mesh.triangles.reserve(static_cast<std::size_t>(4 * n));
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n;
    if (cylinder.top) add(mesh, top_center, k, i);
    add(mesh, i, k + n, i + n);
    add(mesh, i, k, k + n);
    if (cylinder.bottom) add(mesh, bottom_center, i + n, k + n);
  }
  return mesh;
}

// MeshGenerator::generateCone: base ring at y = -h/2, apex at +h/2, base centre.
TriangleMesh cone_mesh(const Cone& cone, int n, Reporter& reporter) {
  const double r = cone.radius, h = cone.height;
  if (!positive(r) || !positive(h)) {
    reporter.report(kRuleInvalidSize, fmt::format("Cone radius {} and height {} must both be positive", r, h));
    return {};
  }
  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(n + 2));
  for (int i = 0; i < n; ++i) {
    const double angle = i * 2.0 * kPi / n;
    mesh.vertices.emplace_back(r * std::cos(angle), -h / 2, r * std::sin(angle));
  }
  const int apex = n, bottom_center = n + 1;
  mesh.vertices.emplace_back(0, h / 2, 0);
  mesh.vertices.emplace_back(0, -h / 2, 0);
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n;
    add(mesh, apex, k, i);
    if (cone.bottom) add(mesh, bottom_center, i, k);
  }
  return mesh;
}

// MeshGenerator::generateCapsule: a sphere whose latitude-band count is rounded up to an even
// number so that the equator is a ring, split there and pulled apart by `height`.
TriangleMesh capsule_mesh(const Capsule& capsule, int n, Reporter& reporter) {
  const double r = capsule.radius, h = capsule.height;
  if (!positive(r) || !non_negative(h)) {
    // §9: height 0 is allowed (a sphere), < 0 or radius <= 0 is an error.
    reporter.report(kRuleInvalidSize,
                    fmt::format("Capsule radius {} must be positive and height {} non-negative", r, h));
    return {};
  }
  int vdn = n / 2;
  if (vdn % 2 != 0) ++vdn;
  const int hdn = n;
  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(vdn * hdn + 2));
  for (int i = 1; i < vdn + 1; ++i) {
    const bool upper_half = i <= vdn / 2;
    const double y = upper_half ? h / 2 : -h / 2;
    const double tv = (upper_half ? i : i - 1) * kPi / vdn;
    for (int j = 0; j < hdn; ++j) {
      const double th = j * 2.0 * kPi / hdn;
      mesh.vertices.emplace_back(r * std::sin(tv) * std::cos(th), r * std::cos(tv) + y,
                                 r * std::sin(tv) * std::sin(th));
    }
  }
  const int top = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0, r + h / 2, 0);
  const int bottom = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0, -r - h / 2, 0);

  for (int i = 0; i < hdn; ++i) add(mesh, top, (i + 1) % hdn, i);
  for (int i = 0; i < vdn - 1; ++i) {
    const int upper = i * hdn, lower = (i + 1) * hdn;
    for (int j = 0; j < hdn; ++j) {
      const int k = (j + 1) % hdn;
      add(mesh, j + upper, k + lower, j + lower);
      add(mesh, j + upper, k + upper, k + lower);
    }
  }
  const int offset = (vdn - 1) * hdn;
  for (int i = 0; i < hdn; ++i) add(mesh, bottom, i + offset, (i + 1) % hdn + offset);
  return mesh;
}

// MeshGenerator::generateElevationGrid; the count check is the one §9 requires (Choreonoid
// would crash on a mismatch).
TriangleMesh elevation_grid_mesh(const ElevationGrid& grid, Reporter& reporter) {
  const int xd = grid.x_dimension, zd = grid.z_dimension;
  if (xd < 0 || zd < 0) {
    reporter.report(kRuleInvalidSize, fmt::format("ElevationGrid dimensions {} x {} must not be negative", xd, zd));
    return {};
  }
  const std::int64_t expected = static_cast<std::int64_t>(xd) * zd;
  if (static_cast<std::int64_t>(grid.height.size()) != expected) {
    reporter.report(kRuleInvalidSize, fmt::format("ElevationGrid has {} height values; x_dimension * z_dimension "
                                                  "= {} x {} = {} are required",
                                                  grid.height.size(), xd, zd, expected));
    return {};
  }
  if (xd < 2 || zd < 2) {
    reporter.report(kRuleDegenerate, fmt::format("ElevationGrid of {} x {} points has no cell (at least 2 x 2 "
                                                 "points are needed)",
                                                 xd, zd));
    return {};
  }
  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(expected));
  for (int z = 0; z < zd; ++z) {
    for (int x = 0; x < xd; ++x) {
      mesh.vertices.emplace_back(x * grid.x_spacing, grid.height[static_cast<std::size_t>(z) * xd + x],
                                 z * grid.z_spacing);
    }
  }
  mesh.triangles.reserve(static_cast<std::size_t>(2 * (xd - 1)) * (zd - 1));
  for (int z = 0; z < zd - 1; ++z) {
    const int current = z * xd, next = (z + 1) * xd;
    for (int x = 0; x < xd - 1; ++x) {
      // ccw: the surface faces +Y (for positive spacings), as VRML97 defines it.
      if (grid.ccw) {
        add(mesh, x + current, x + next, x + 1 + next);
        add(mesh, x + current, x + 1 + next, x + 1 + current);
      } else {
        add(mesh, x + current, x + 1 + next, x + next);
        add(mesh, x + current, x + 1 + current, x + 1 + next);
      }
    }
  }
  return mesh;
}

// IndexedFaceSet: coordIndex polygons terminated by -1 (§9). Polygons with a bad index are
// skipped whole; the rest of the mesh is still produced. `origins` gets, per triangle, the
// position in `faces` where its polygon starts.
TriangleMesh face_set_mesh(const IndexedFaceSet& face_set, Reporter& reporter, std::vector<std::size_t>& origins) {
  TriangleMesh mesh;
  mesh.vertices = face_set.vertices;
  const std::size_t num_vertices = face_set.vertices.size();
  std::vector<int> polygon;
  int polygon_number = 0;
  bool reported = false;
  std::size_t polygon_start = 0;
  for (std::size_t position = 0; position < face_set.faces.size(); ++position) {
    const int index = face_set.faces[position];
    if (index != -1) {
      polygon.push_back(index);
      continue;
    }
    bool indices_ok = true;
    for (int i : polygon) {
      if (i < 0 || static_cast<std::size_t>(i) >= num_vertices) {
        reporter.report(kRuleIndexOutOfRange, fmt::format("IndexedFaceSet polygon {}: vertex index {} is out of range "
                                                          "(the face set has {} vertices)",
                                                          polygon_number, i, num_vertices));
        indices_ok = false;
        reported = true;
        break;
      }
    }
    bool over_budget = false;
    if (indices_ok && !triangulate_polygon(mesh.vertices, polygon, mesh.triangles, &over_budget)) {
      reporter.report(kRuleDegenerate,
                      over_budget ? fmt::format("IndexedFaceSet polygon {} ({} indices) crosses itself too often to "
                                                "be triangulated within the tessellation budget; it is left out",
                                                polygon_number, polygon.size())
                                  : fmt::format("IndexedFaceSet polygon {} ({} indices) has fewer than three "
                                                "distinct points or no area",
                                                polygon_number, polygon.size()));
      reported = true;
    }
    origins.resize(mesh.triangles.size(), polygon_start);
    polygon_start = position + 1;
    polygon.clear();
    ++polygon_number;
  }
  // A trailing polygon without -1 is dropped silently, as Choreonoid does (§9, §15); the
  // loader flags it.
  if (mesh.triangles.empty() && !reported) {
    reporter.report(kRuleDegenerate, "IndexedFaceSet has no valid polygon");
  }
  return mesh;
}

// TriangleMesh geometry: `faces` is a flat list of triangles (§9). Kept as given, including
// zero-area triangles, so that indices match the file. `origins` gets, per triangle, the
// position of its first index in `faces`.
TriangleMesh triangle_list_mesh(const TriangleMeshGeometry& geometry, Reporter& reporter,
                                std::vector<std::size_t>& origins) {
  TriangleMesh mesh;
  mesh.vertices = geometry.vertices;
  const std::size_t num_vertices = geometry.vertices.size();
  const std::size_t num_full = geometry.faces.size() / 3 * 3;
  mesh.triangles.reserve(num_full / 3);
  for (std::size_t k = 0; k < num_full; k += 3) {
    std::array<int, 3> t{geometry.faces[k], geometry.faces[k + 1], geometry.faces[k + 2]};
    bool ok = true;
    for (int i : t) {
      if (i < 0 || static_cast<std::size_t>(i) >= num_vertices) {
        reporter.report(kRuleIndexOutOfRange, fmt::format("TriangleMesh triangle {}: vertex index {} is out of range "
                                                          "(the mesh has {} vertices)",
                                                          k / 3, i, num_vertices));
        ok = false;
        break;
      }
    }
    if (ok) {
      mesh.triangles.push_back(t);
      origins.push_back(k);
    }
  }
  if (num_full != geometry.faces.size()) {
    reporter.report(kRuleDegenerate, fmt::format("TriangleMesh faces has {} indices, not a multiple of 3; the "
                                                 "last {} are ignored",
                                                 geometry.faces.size(), geometry.faces.size() - num_full));
  }
  if (geometry.faces.empty()) reporter.report(kRuleDegenerate, "TriangleMesh has no triangle");
  return mesh;
}

}  // namespace

int effective_division_number(int division_number) {
  return division_number < 4 ? kDefaultDivisionNumber : division_number;
}

namespace detail {

TriangleMesh tessellate_with(const Geometry& geometry, int division_number, DiagnosticSink& sink,
                             const SourceLocation& where, TexCoords tex_coords, ExtrusionFrames frames) {
  Reporter reporter(sink, where);
  int n = effective_division_number(division_number);
  const bool uses_division = std::holds_alternative<Sphere>(geometry) || std::holds_alternative<Cylinder>(geometry) ||
                             std::holds_alternative<Cone>(geometry) || std::holds_alternative<Capsule>(geometry);
  if (uses_division && n > kMaxDivisionNumber) {
    reporter.report("geometry-division-clamped",
                    fmt::format("division_number {} exceeds the tessellator's limit {}; {} is "
                                "used",
                                n, kMaxDivisionNumber, kMaxDivisionNumber));
    n = kMaxDivisionNumber;
  }
  std::vector<std::size_t> origins;  // per triangle of a face list: where it comes from
  struct Visitor {
    int n;
    ExtrusionFrames frames;
    Reporter& reporter;
    std::vector<std::size_t>& origins;
    TriangleMesh operator()(const Box& g) const { return box_mesh(g, reporter); }
    TriangleMesh operator()(const Sphere& g) const { return sphere_mesh(g, n, reporter); }
    TriangleMesh operator()(const Cylinder& g) const { return cylinder_mesh(g, n, reporter); }
    TriangleMesh operator()(const Cone& g) const { return cone_mesh(g, n, reporter); }
    TriangleMesh operator()(const Capsule& g) const { return capsule_mesh(g, n, reporter); }
    TriangleMesh operator()(const Extrusion& g) const { return detail::tessellate_extrusion(g, frames, reporter); }
    TriangleMesh operator()(const ElevationGrid& g) const { return elevation_grid_mesh(g, reporter); }
    TriangleMesh operator()(const IndexedFaceSet& g) const { return face_set_mesh(g, reporter, origins); }
    TriangleMesh operator()(const TriangleMeshGeometry& g) const { return triangle_list_mesh(g, reporter, origins); }
    TriangleMesh operator()(const MeshResource&) const { return {}; }
  };
  TriangleMesh mesh = std::visit(Visitor{n, frames, reporter, origins}, geometry);
  if (tex_coords == TexCoords::kGenerate && !mesh.empty()) return detail::with_tex_coords(mesh, geometry, n, origins);
  return mesh;
}

}  // namespace detail

TriangleMesh tessellate(const Shape& shape, DiagnosticSink& sink, TexCoords tex_coords) {
  return tessellate(shape.geometry, shape.division_number, sink, shape.source, tex_coords);
}

}  // namespace bodyfmt
