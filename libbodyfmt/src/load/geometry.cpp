#include "load/geometry.h"

#include <bodyfmt/body_keys.h>

#include <bodyfmt/tessellate.h>

#include "load/mapping_reader.h"
#include "load/scalar.h"
#include "load/uri.h"
#include "load/values.h"
#include "text/text_util.h"

#include <algorithm>

namespace bodyfmt::detail {
namespace {

std::vector<Eigen::Vector2d> pairs(const std::vector<double>& v) {
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i + 1 < v.size(); i += 2) out.emplace_back(v[i], v[i + 1]);
  return out;
}

std::vector<Eigen::Vector3d> triples(const std::vector<double>& v) {
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i + 2 < v.size(); i += 3) out.emplace_back(v[i], v[i + 1], v[i + 2]);
  return out;
}

std::vector<int> indices(LoadContext& ctx, const yaml::NodeRef& ref) {
  std::vector<int> out;
  if (!ref || !listing_or_ignored(ctx, ref, "an index list")) return out;  // findListing
  for (const yaml::NodeRef& item : ref->items()) {
    auto v = required_int(ctx, item);
    out.push_back(v ? static_cast<int>(*v) : -1);
  }
  return out;
}

std::vector<double> numbers_or_empty(LoadContext& ctx, const yaml::NodeRef& ref) {
  // Every number list of a geometry is read with findListing: another type is skipped.
  if (!ref || !listing_or_ignored(ctx, ref, "this list")) return {};
  auto v = read_numbers(ctx, ref);
  return v ? *v : std::vector<double>{};
}

void check_positive(LoadContext& ctx, MappingReader& r, const char* key, double value) {
  if (value <= 0) {
    ctx.report("geometry-invalid-size", r.node()->find(key) ? r.node()->find(key)->value : r.node(),
               std::string(key) + " must be positive, found " + std::to_string(value));
  }
}

Geometry read_box(LoadContext& ctx, MappingReader& r) {
  Box box;
  if (yaml::NodeRef size = r.take({"size"})) assign_if(box.size, read_optional_vec3(ctx, size));
  if ((box.size.array() < 0).any())
    ctx.report("geometry-invalid-size", r.node()->find("size")->value, "a box cannot have a negative size");
  r.report_unknown(body_key_names("geometry:Box"));
  return box;
}

Geometry read_sphere(LoadContext& ctx, MappingReader& r) {
  Sphere s;
  assign_if(s.radius, take_optional_double(r, {"radius"}));
  check_positive(ctx, r, "radius", s.radius);
  r.report_unknown(body_key_names("geometry:Sphere"));
  return s;
}

Geometry read_cylinder(LoadContext& ctx, MappingReader& r) {
  Cylinder c;
  assign_if(c.radius, take_optional_double(r, {"radius"}));
  assign_if(c.height, take_optional_double(r, {"height"}));
  assign_if(c.top, take_optional_bool(r, {"top"}));
  assign_if(c.bottom, take_optional_bool(r, {"bottom"}));
  check_positive(ctx, r, "radius", c.radius);
  check_positive(ctx, r, "height", c.height);
  r.report_unknown(body_key_names("geometry:Cylinder"));
  return c;
}

Geometry read_cone(LoadContext& ctx, MappingReader& r) {
  Cone c;
  assign_if(c.radius, take_optional_double(r, {"radius"}));
  assign_if(c.height, take_optional_double(r, {"height"}));
  assign_if(c.bottom, take_optional_bool(r, {"bottom"}));
  check_positive(ctx, r, "radius", c.radius);
  check_positive(ctx, r, "height", c.height);
  r.report_unknown(body_key_names("geometry:Cone"));
  return c;
}

Geometry read_capsule(LoadContext& ctx, MappingReader& r) {
  Capsule c;
  assign_if(c.radius, take_optional_double(r, {"radius"}));
  assign_if(c.height, take_optional_double(r, {"height"}));
  check_positive(ctx, r, "radius", c.radius);
  if (c.height < 0)  // height 0 is a sphere, which Choreonoid allows
    ctx.report("geometry-invalid-size", r.node()->find("height")->value, "capsule height must not be negative");
  r.report_unknown(body_key_names("geometry:Capsule"));
  return c;
}

Geometry read_extrusion(LoadContext& ctx, MappingReader& r) {
  Extrusion e;
  e.cross_section = pairs(numbers_or_empty(ctx, r.take({"cross_section", "crossSection"})));
  e.spine = triples(numbers_or_empty(ctx, r.take({"spine"})));
  yaml::NodeRef orientation_node = r.take({"orientation"});
  std::vector<double> orientation = numbers_or_empty(ctx, orientation_node);
  for (std::size_t i = 0; i + 3 < orientation.size(); i += 4) {
    Eigen::Vector3d axis(orientation[i], orientation[i + 1], orientation[i + 2]);
    double angle = ctx.angle(orientation[i + 3], orientation_node.child(orientation_node->items()[i + 3]));
    // The axis as written: Choreonoid does not normalise it (see ExtrusionFrames).
    e.orientation.emplace_back(angle, axis);
  }
  e.scale = pairs(numbers_or_empty(ctx, r.take({"scale"})));
  assign_if(e.crease_angle, take_optional_angle(r, {"crease_angle", "creaseAngle"}));
  // body-format-spec §9: only the camelCase `beginCap` is read by Choreonoid.
  assign_if(e.begin_cap, take_optional_bool(r, {"beginCap"}));
  assign_if(e.end_cap, take_optional_bool(r, {"end_cap", "endCap"}));
  r.ignore("solid");
  const yaml::NodeRef where = r.node();
  if (r.has({"begin_cap"})) {
    ctx.report("load-ignored-key", r.node()->find("begin_cap")->value,
               "Choreonoid does not read \"begin_cap\"; only \"beginCap\" works", "rename it to beginCap");
    r.ignore("begin_cap");
  }
  // Fewer than two points crash Choreonoid (null mesh), §9.
  if (e.cross_section.size() < 2)
    ctx.report("geometry-degenerate", where, "an Extrusion needs at least 2 cross-section points");
  if (e.spine.size() < 2) ctx.report("geometry-degenerate", where, "an Extrusion needs at least 2 spine points");
  auto check_count = [&](std::size_t n, const char* key) {
    if (n > 1 && n != e.spine.size())
      ctx.report("geometry-degenerate", where,
                 std::string(key) + " must have 1 entry or one per spine point (" + std::to_string(e.spine.size()) +
                     "), found " + std::to_string(n));
  };
  check_count(e.orientation.size(), "orientation");
  check_count(e.scale.size(), "scale");
  r.report_unknown(body_key_names("geometry:Extrusion"));
  return e;
}

Geometry read_elevation_grid(LoadContext& ctx, MappingReader& r) {
  ElevationGrid g;
  if (auto v = r.take({"x_dimension", "xDimension"}))
    assign_if(g.x_dimension, std::optional<int>(optional_int(ctx, v).value_or(0)));
  if (auto v = r.take({"z_dimension", "zDimension"}))
    assign_if(g.z_dimension, std::optional<int>(optional_int(ctx, v).value_or(0)));
  assign_if(g.x_spacing, take_optional_double(r, {"x_spacing", "xSpacing"}));
  assign_if(g.z_spacing, take_optional_double(r, {"z_spacing", "zSpacing"}));
  g.height = numbers_or_empty(ctx, r.take({"height"}));
  assign_if(g.ccw, take_optional_bool(r, {"ccw"}));
  assign_if(g.crease_angle, take_optional_angle(r, {"crease_angle", "creaseAngle"}));
  r.take({"tex_coord", "texCoord"});
  r.ignore("solid");
  if (g.x_dimension < 2 || g.z_dimension < 2)
    ctx.report("geometry-degenerate", r.node(), "an ElevationGrid needs x_dimension and z_dimension of at least 2");
  else if (g.height.size() != static_cast<std::size_t>(g.x_dimension) * g.z_dimension)
    ctx.report("geometry-degenerate", r.node(),
               "an ElevationGrid needs x_dimension * z_dimension = " + std::to_string(g.x_dimension * g.z_dimension) +
                   " heights, found " + std::to_string(g.height.size()));
  r.report_unknown(body_key_names("geometry:ElevationGrid"));
  return g;
}

template <typename MeshGeometry>
MeshGeometry read_mesh_keys(LoadContext& ctx, MappingReader& r) {
  MeshGeometry m;
  m.vertices = triples(numbers_or_empty(ctx, r.take({"vertices", "coordinate"})));
  m.faces = indices(ctx, r.take({"faces", "coordIndex"}));
  m.tex_coords = pairs(numbers_or_empty(ctx, r.take({"tex_coords", "texCoord"})));
  m.tex_coord_indices = indices(ctx, r.take({"tex_coord_indices", "texCoordIndex"}));
  assign_if(m.crease_angle, take_optional_angle(r, {"crease_angle", "creaseAngle"}));
  for (const char* k : {"normals", "normal_indices", "solid"}) r.ignore(k);
  r.take({"remove_redundant_vertices", "removeRedundantVertices"});
  const int n = static_cast<int>(m.vertices.size());
  for (int index : m.faces) {
    if (index >= n || index < -1) {
      ctx.report("geometry-index-out-of-range",
                 r.node()->find("faces") ? r.node()->find("faces")->value : r.node()->find("coordIndex")->value,
                 "vertex index " + std::to_string(index) + " is out of range (" + std::to_string(n) + " vertices)");
      break;
    }
  }
  r.report_unknown(body_key_names("geometry:IndexedFaceSet"));  // TriangleMesh: the same keys
  return m;
}

Geometry read_indexed_face_set(LoadContext& ctx, MappingReader& r) {
  auto m = read_mesh_keys<IndexedFaceSet>(ctx, r);
  // A polygon needs three indices before its -1; Choreonoid refuses a set with none.
  int run = 0;
  bool any_polygon = false;
  for (int index : m.faces) {
    if (index == -1) {
      any_polygon = any_polygon || run >= 3;
      run = 0;
    } else {
      ++run;
    }
  }
  if (!any_polygon)
    ctx.report("geometry-degenerate", r.node(), "this IndexedFaceSet has no polygon with three or more vertices");
  if (!m.faces.empty() && m.faces.back() != -1) {
    // body-format-spec §9: Choreonoid silently drops a last polygon not closed by -1.
    const yaml::MapEntry* faces = r.node()->find("faces");
    if (!faces) faces = r.node()->find("coordIndex");
    ctx.report("geometry-unterminated-polygon", faces ? faces->value : r.node(),
               "the last polygon of this IndexedFaceSet is not terminated by -1; Choreonoid drops it",
               "append -1 to faces");
  }
  return m;
}

Geometry read_triangle_mesh(LoadContext& ctx, MappingReader& r) {
  auto m = read_mesh_keys<TriangleMeshGeometry>(ctx, r);
  if (m.faces.size() % 3 != 0)
    ctx.report("geometry-degenerate", r.node(), "TriangleMesh faces must be a multiple of 3 indices");
  else if (m.faces.empty())
    ctx.report("geometry-degenerate", r.node(), "this TriangleMesh has no triangle");
  return m;
}

Geometry read_resource_geometry(LoadContext& ctx, MappingReader& r) {
  MeshResource mesh;
  yaml::NodeRef uri = r.take({"uri"});
  if (!uri) {
    ctx.report("load-missing-key", r.node(), "key \"uri\" is not found in a Resource geometry");
  } else if (auto text = required_string(ctx, uri)) {
    mesh.uri = *text;
    mesh.uri_source = uri.use_site();
    mesh.resolved_path = resolve_uri(ctx, uri, mesh.uri, uri->location.file);
  }
  if (auto node = take_resource_node(ctx, r)) mesh.node = required_string(ctx, node).value_or("");
  if (auto metadata = r.take({"metadata"})) read_mesh_metadata(ctx, metadata, mesh);
  if (auto crease = take_optional_angle(r, {"crease_angle", "creaseAngle"})) mesh.crease_angle = *crease;
  r.take({"remove_redundant_vertices", "removeRedundantVertices"});
  r.report_unknown(body_key_names("geometry:Resource"));
  return mesh;
}

}  // namespace

int division_number_from(LoadContext& ctx, const yaml::NodeRef& at, long n, std::string_view key) {
  if (n > kMaxDivisionNumber)
    ctx.report("geometry-division-clamped", at,
               std::string(key) + " " + std::to_string(n) + " is clamped to " + std::to_string(kMaxDivisionNumber),
               "a sphere has about n^2/2 vertices; use a smaller " + std::string(key));
  return n < 4 ? 20 : static_cast<int>(std::min<long>(n, kMaxDivisionNumber));
}

yaml::NodeRef take_resource_node(LoadContext& ctx, MappingReader& r) {
  if (!r.has({"fragment"}) || !r.has({"node"})) return r.take({"node", "fragment"});
  yaml::NodeRef fragment = r.take({"fragment"});
  ctx.report("load-ignored-key", r.take({"node"}), "Choreonoid reads fragment before node: this node is ignored",
             "keep one of them");
  return fragment;
}

std::optional<Geometry> read_geometry(LoadContext& ctx, const yaml::NodeRef& geometry, int& division_number) {
  if (!mapping_or_ignored(ctx, geometry, "geometry")) return std::nullopt;  // findMapping: no geometry
  MappingReader r(ctx, geometry, "geometry");
  yaml::NodeRef type = r.take({"type"});
  if (!type) {
    ctx.report("load-missing-key", geometry, "key \"type\" is not found in the geometry");
    return std::nullopt;
  }
  if (auto division = r.take({"division_number", "divisionNumber"})) {
    if (auto n = optional_int(ctx, division))
      division_number = division_number_from(ctx, division, *n, "division_number");
  }
  r.take({"extra_division_number"});
  r.take({"extra_division_mode"});
  r.ignore("appearance");  // a Shape's key one level too deep: read_shape reports it (load-misplaced-key)
  const std::string_view t = type->scalar();
  if (t == "Box") return read_box(ctx, r);
  if (t == "Sphere") return read_sphere(ctx, r);
  if (t == "Cylinder") return read_cylinder(ctx, r);
  if (t == "Cone") return read_cone(ctx, r);
  if (t == "Capsule") return read_capsule(ctx, r);
  if (t == "Extrusion") return read_extrusion(ctx, r);
  if (t == "ElevationGrid") return read_elevation_grid(ctx, r);
  if (t == "IndexedFaceSet") return read_indexed_face_set(ctx, r);
  if (t == "TriangleMesh") return read_triangle_mesh(ctx, r);
  if (t == "Resource") return read_resource_geometry(ctx, r);
  std::string_view guess = text::suggest(t, geometry_type_names());
  ctx.report("geometry-unknown-type", type, "unknown geometry \"" + std::string(t) + "\"",
             guess.empty() ? std::string() : "did you mean " + std::string(guess) + "?");
  return std::nullopt;
}

}  // namespace bodyfmt::detail
