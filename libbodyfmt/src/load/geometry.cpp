#include "load/geometry.h"

#include <bodyfmt/tessellate.h>

#include "load/mapping_reader.h"
#include "load/scalar.h"
#include "load/values.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace bodyfmt::detail {
namespace {

const std::vector<std::string_view> kPrimitiveCommonKeys = {
    "type", "division_number", "divisionNumber", "extra_division_number", "extra_division_mode"};

std::optional<double> opt_double(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  return optional_double(r.context(), ref);
}

std::optional<bool> opt_bool(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  return optional_bool(r.context(), ref);
}

template <typename T>
void set_if(T& target, const std::optional<T>& value) {
  if (value) target = *value;
}

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
  if (!ref || !ref->is_sequence()) {
    if (ref) ctx.error("load-type", ref, "an index list must be a sequence");
    return out;
  }
  for (const yaml::NodeRef& item : ref->items) {
    auto v = required_int(ctx, item);
    out.push_back(v ? static_cast<int>(*v) : -1);
  }
  return out;
}

std::vector<double> numbers_or_empty(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!ref) return {};
  auto v = read_numbers(ctx, ref);
  return v ? *v : std::vector<double>{};
}

void check_positive(LoadContext& ctx, MappingReader& r, const char* key, double value) {
  if (value <= 0) {
    ctx.error("geometry-invalid-size", r.node()->find(key) ? r.node()->find(key)->value : r.node(),
              std::string(key) + " must be positive, found " + std::to_string(value));
  }
}

Geometry read_box(LoadContext& ctx, MappingReader& r) {
  Box box;
  if (yaml::NodeRef size = r.take({"size"})) set_if(box.size, read_optional_vec3(ctx, size));
  if ((box.size.array() < 0).any())
    ctx.error("geometry-invalid-size", r.node()->find("size")->value,
              "a box cannot have a negative size");
  r.report_unknown({"size", "type", "division_number", "extra_division_mode"});
  return box;
}

Geometry read_sphere(LoadContext& ctx, MappingReader& r) {
  Sphere s;
  set_if(s.radius, opt_double(r, {"radius"}));
  check_positive(ctx, r, "radius", s.radius);
  r.report_unknown({"radius", "type", "division_number"});
  return s;
}

Geometry read_cylinder(LoadContext& ctx, MappingReader& r) {
  Cylinder c;
  set_if(c.radius, opt_double(r, {"radius"}));
  set_if(c.height, opt_double(r, {"height"}));
  set_if(c.top, opt_bool(r, {"top"}));
  set_if(c.bottom, opt_bool(r, {"bottom"}));
  check_positive(ctx, r, "radius", c.radius);
  check_positive(ctx, r, "height", c.height);
  r.report_unknown({"radius", "height", "top", "bottom", "type", "division_number"});
  return c;
}

Geometry read_cone(LoadContext& ctx, MappingReader& r) {
  Cone c;
  set_if(c.radius, opt_double(r, {"radius"}));
  set_if(c.height, opt_double(r, {"height"}));
  set_if(c.bottom, opt_bool(r, {"bottom"}));
  check_positive(ctx, r, "radius", c.radius);
  check_positive(ctx, r, "height", c.height);
  r.report_unknown({"radius", "height", "bottom", "type", "division_number"});
  return c;
}

Geometry read_capsule(LoadContext& ctx, MappingReader& r) {
  Capsule c;
  set_if(c.radius, opt_double(r, {"radius"}));
  set_if(c.height, opt_double(r, {"height"}));
  check_positive(ctx, r, "radius", c.radius);
  if (c.height < 0)  // height 0 is a sphere, which Choreonoid allows
    ctx.error("geometry-invalid-size", r.node()->find("height")->value,
              "capsule height must not be negative");
  r.report_unknown({"radius", "height", "type", "division_number"});
  return c;
}

Geometry read_extrusion(LoadContext& ctx, MappingReader& r) {
  Extrusion e;
  e.cross_section = pairs(numbers_or_empty(ctx, r.take({"cross_section", "crossSection"})));
  e.spine = triples(numbers_or_empty(ctx, r.take({"spine"})));
  std::vector<double> orientation = numbers_or_empty(ctx, r.take({"orientation"}));
  for (std::size_t i = 0; i + 3 < orientation.size(); i += 4) {
    Eigen::Vector3d axis(orientation[i], orientation[i + 1], orientation[i + 2]);
    double angle = ctx.angle(orientation[i + 3]);
    e.orientation.emplace_back(angle, axis.norm() > 0 ? Eigen::Vector3d(axis.normalized())
                                                      : Eigen::Vector3d::UnitZ());
  }
  e.scale = pairs(numbers_or_empty(ctx, r.take({"scale"})));
  if (auto crease = opt_double(r, {"crease_angle", "creaseAngle"})) e.crease_angle = ctx.angle(*crease);
  // body-format-spec §9: only the camelCase `beginCap` is read by Choreonoid.
  set_if(e.begin_cap, opt_bool(r, {"beginCap"}));
  set_if(e.end_cap, opt_bool(r, {"end_cap", "endCap"}));
  r.ignore("solid");
  const yaml::NodeRef where = r.node();
  if (r.has({"begin_cap"})) {
    ctx.warning("load-ignored-key", r.node()->find("begin_cap")->value,
                "Choreonoid does not read \"begin_cap\"; only \"beginCap\" works", "rename it to beginCap");
    r.ignore("begin_cap");
  }
  // Fewer than two points crash Choreonoid (null mesh), §9.
  if (e.cross_section.size() < 2)
    ctx.error("geometry-degenerate", where, "an Extrusion needs at least 2 cross-section points");
  if (e.spine.size() < 2) ctx.error("geometry-degenerate", where, "an Extrusion needs at least 2 spine points");
  auto check_count = [&](std::size_t n, const char* key) {
    if (n > 1 && n != e.spine.size())
      ctx.error("geometry-degenerate", where,
                std::string(key) + " must have 1 entry or one per spine point (" +
                    std::to_string(e.spine.size()) + "), found " + std::to_string(n));
  };
  check_count(e.orientation.size(), "orientation");
  check_count(e.scale.size(), "scale");
  r.report_unknown({"cross_section", "spine", "orientation", "scale", "crease_angle", "beginCap",
                    "end_cap", "solid", "type"});
  return e;
}

Geometry read_elevation_grid(LoadContext& ctx, MappingReader& r) {
  ElevationGrid g;
  if (auto v = r.take({"x_dimension", "xDimension"})) set_if(g.x_dimension, std::optional<int>(optional_int(ctx, v).value_or(0)));
  if (auto v = r.take({"z_dimension", "zDimension"})) set_if(g.z_dimension, std::optional<int>(optional_int(ctx, v).value_or(0)));
  set_if(g.x_spacing, opt_double(r, {"x_spacing", "xSpacing"}));
  set_if(g.z_spacing, opt_double(r, {"z_spacing", "zSpacing"}));
  g.height = numbers_or_empty(ctx, r.take({"height"}));
  set_if(g.ccw, opt_bool(r, {"ccw"}));
  if (auto crease = opt_double(r, {"crease_angle", "creaseAngle"})) g.crease_angle = ctx.angle(*crease);
  r.take({"tex_coord", "texCoord"});
  r.ignore("solid");
  if (g.x_dimension < 2 || g.z_dimension < 2)
    ctx.error("geometry-degenerate", r.node(), "an ElevationGrid needs x_dimension and z_dimension of at least 2");
  else if (g.height.size() != static_cast<std::size_t>(g.x_dimension) * g.z_dimension)
    ctx.error("geometry-degenerate", r.node(),
              "an ElevationGrid needs x_dimension * z_dimension = " +
                  std::to_string(g.x_dimension * g.z_dimension) + " heights, found " +
                  std::to_string(g.height.size()));
  r.report_unknown({"x_dimension", "z_dimension", "x_spacing", "z_spacing", "height", "ccw",
                    "crease_angle", "tex_coord", "solid", "type"});
  return g;
}

template <typename MeshGeometry>
MeshGeometry read_mesh_keys(LoadContext& ctx, MappingReader& r) {
  MeshGeometry m;
  m.vertices = triples(numbers_or_empty(ctx, r.take({"vertices", "coordinate"})));
  m.faces = indices(ctx, r.take({"faces", "coordIndex"}));
  m.tex_coords = pairs(numbers_or_empty(ctx, r.take({"tex_coords", "texCoord"})));
  m.tex_coord_indices = indices(ctx, r.take({"tex_coord_indices", "texCoordIndex"}));
  if (auto crease = opt_double(r, {"crease_angle", "creaseAngle"})) m.crease_angle = ctx.angle(*crease);
  for (const char* k : {"normals", "normal_indices", "solid"}) r.ignore(k);
  r.take({"remove_redundant_vertices", "removeRedundantVertices"});
  const int n = static_cast<int>(m.vertices.size());
  for (int index : m.faces) {
    if (index >= n || index < -1) {
      ctx.error("geometry-index-out-of-range", r.node()->find("faces") ? r.node()->find("faces")->value
                                                                      : r.node()->find("coordIndex")->value,
                "vertex index " + std::to_string(index) + " is out of range (" + std::to_string(n) +
                    " vertices)");
      break;
    }
  }
  r.report_unknown({"vertices", "faces", "tex_coords", "tex_coord_indices", "crease_angle",
                    "normals", "normal_indices", "solid", "remove_redundant_vertices", "type"});
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
    ctx.error("geometry-degenerate", r.node(), "this IndexedFaceSet has no polygon with three or more vertices");
  if (!m.faces.empty() && m.faces.back() != -1) {
    // body-format-spec §9: Choreonoid silently drops a last polygon not closed by -1.
    const yaml::MapEntry* faces = r.node()->find("faces");
    if (!faces) faces = r.node()->find("coordIndex");
    ctx.warning("geometry-unterminated-polygon", faces ? faces->value : r.node(),
                "the last polygon of this IndexedFaceSet is not terminated by -1; Choreonoid drops it",
                "append -1 to faces");
  }
  return m;
}

Geometry read_triangle_mesh(LoadContext& ctx, MappingReader& r) {
  auto m = read_mesh_keys<TriangleMeshGeometry>(ctx, r);
  if (m.faces.size() % 3 != 0)
    ctx.error("geometry-degenerate", r.node(), "TriangleMesh faces must be a multiple of 3 indices");
  else if (m.faces.empty())
    ctx.error("geometry-degenerate", r.node(), "this TriangleMesh has no triangle");
  return m;
}

Geometry read_resource_geometry(LoadContext& ctx, MappingReader& r) {
  MeshResource mesh;
  yaml::NodeRef uri = r.take({"uri"});
  if (!uri) {
    ctx.error("load-missing-key", r.node(), "key \"uri\" is not found in a Resource geometry");
  } else if (auto text = required_string(ctx, uri)) {
    mesh.uri = *text;
    mesh.resolved_path = resolve_uri(ctx, uri, mesh.uri, uri->location.file);
  }
  if (auto node = r.take({"node", "fragment"})) mesh.node = required_string(ctx, node).value_or("");
  if (auto metadata = r.take({"metadata"})) read_mesh_metadata(ctx, metadata, mesh);
  if (auto crease = opt_double(r, {"crease_angle", "creaseAngle"})) mesh.crease_angle = ctx.angle(*crease);
  r.take({"remove_redundant_vertices", "removeRedundantVertices"});
  r.report_unknown({"uri", "node", "fragment", "metadata", "crease_angle", "remove_redundant_vertices", "type"});
  return mesh;
}

}  // namespace

std::string resolve_uri(LoadContext& ctx, const yaml::NodeRef& at, const std::string& uri,
                        const std::string& referring_file) {
  namespace fs = std::filesystem;
  std::string path = uri;
  const std::string file_scheme = "file://";
  if (path.rfind(file_scheme, 0) == 0) path = path.substr(file_scheme.size());
  auto scheme_end = path.find("://");
  if (scheme_end != std::string::npos) {
    std::string scheme = path.substr(0, scheme_end);
    if (scheme != "package") {
      ctx.error("load-uri", at, "the \"" + scheme + "\" scheme in URI \"" + uri + "\" is not supported");
      return {};
    }
    // package://NAME/rest through ROS_PACKAGE_PATH.
    std::string rest = path.substr(scheme_end + 3);
    std::string package = rest.substr(0, rest.find('/'));
    std::string inside = rest.find('/') == std::string::npos ? "" : rest.substr(rest.find('/') + 1);
    for (const std::string& root : ctx.package_paths) {
      fs::path candidate = fs::path(root) / package / inside;
      if (fs::exists(candidate)) return candidate.lexically_normal().string();
    }
    if (const char* roots = std::getenv("ROS_PACKAGE_PATH")) {
      std::string all = roots;
      std::size_t start = 0;
      while (start <= all.size()) {
        std::size_t end = all.find(':', start);
        std::string root = all.substr(start, end == std::string::npos ? std::string::npos : end - start);
        fs::path candidate = fs::path(root) / package / inside;
        if (!root.empty() && fs::exists(candidate)) return candidate.lexically_normal().string();
        if (end == std::string::npos) break;
        start = end + 1;
      }
    }
    ctx.error("load-uri", at, "package \"" + package + "\" of URI \"" + uri + "\" is not found",
              "add its parent folder to ROS_PACKAGE_PATH or pass it as a package path");
    return {};
  }
  if (path.rfind("${", 0) == 0) {
    auto close = path.find('}');
    std::string variable = path.substr(2, close == std::string::npos ? std::string::npos : close - 2);
    const char* value = variable == "HOME" ? std::getenv("HOME") : nullptr;
    if (!value) {
      ctx.error("load-uri", at, "path variable \"" + variable + "\" in \"" + uri + "\" is not defined");
      return {};
    }
    path = std::string(value) + path.substr(close + 1);
  }
  fs::path p(path);
  if (p.is_relative()) p = fs::path(referring_file).parent_path() / p;
  return p.lexically_normal().string();
}

void read_mesh_metadata(LoadContext& ctx, const yaml::NodeRef& metadata, MeshResource& mesh) {
  auto apply_unit = [&](const std::string& unit, const yaml::NodeRef& at) {
    if (unit == "millimeter") mesh.length_scale = 0.001;
    else if (unit == "inch") mesh.length_scale = 0.0254;
    else if (unit == "meter") mesh.length_scale = 1.0;
    else ctx.warning("load-ignored-value", at, "unknown length unit \"" + unit + "\"");
  };
  if (metadata->is_scalar()) {
    // Legacy form: space-separated words (body-format-spec §9.4).
    std::string words = metadata->scalar;
    std::size_t start = 0;
    while (start < words.size()) {
      std::size_t end = words.find(' ', start);
      std::string word = words.substr(start, end - start);
      if (word == "y_upper") mesh.y_up = true;
      else if (!word.empty()) apply_unit(word, metadata);
      if (end == std::string::npos) break;
      start = end + 1;
    }
    return;
  }
  MappingReader r(ctx, metadata, "metadata");
  if (auto unit = r.take({"length_unit"})) apply_unit(unit->scalar, unit);
  if (auto axis = r.take({"upper_axis"})) {
    if (axis->scalar == "Y") mesh.y_up = true;
    else if (axis->scalar != "Z") ctx.warning("load-ignored-value", axis, "upper_axis must be Y or Z");
  }
  r.report_unknown({"length_unit", "upper_axis"});
}

std::optional<Geometry> read_geometry(LoadContext& ctx, const yaml::NodeRef& geometry,
                                      int& division_number) {
  if (!geometry->is_mapping()) {
    ctx.error("load-type", geometry, "geometry must be a mapping");
    return std::nullopt;
  }
  MappingReader r(ctx, geometry, "geometry");
  yaml::NodeRef type = r.take({"type"});
  if (!type) {
    ctx.error("load-missing-key", geometry, "key \"type\" is not found in the geometry");
    return std::nullopt;
  }
  if (auto division = r.take({"division_number", "divisionNumber"})) {
    if (auto n = optional_int(ctx, division)) {
      division_number = *n < 4 ? 20 : static_cast<int>(std::min<long>(*n, kMaxDivisionNumber));
      if (*n > kMaxDivisionNumber)
        ctx.warning("geometry-invalid-size", division,
                    "division_number " + std::to_string(*n) + " is clamped to " + std::to_string(kMaxDivisionNumber),
                    "a sphere has about n^2/2 vertices; use a smaller division_number");
    }
  }
  r.take({"extra_division_number"});
  r.take({"extra_division_mode"});
  const std::string& t = type->scalar;
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
  static const std::vector<std::string_view> kTypes = {
      "Box", "Sphere", "Cylinder", "Cone", "Capsule", "Extrusion", "ElevationGrid",
      "IndexedFaceSet", "TriangleMesh", "Resource"};
  std::string_view guess = suggest(t, kTypes);
  ctx.error("geometry-unknown-type", type, "unknown geometry \"" + t + "\"",
            guess.empty() ? std::string() : "did you mean " + std::string(guess) + "?");
  return std::nullopt;
}

Appearance read_appearance(LoadContext& ctx, const yaml::NodeRef& appearance) {
  Appearance result;
  if (!appearance->is_mapping()) {
    // Choreonoid reads appearance as an optional mapping: anything else is ignored (SR1DH
    // has an empty `appearance:` whose material slipped to the Shape's indentation level).
    ctx.warning("load-ignored-value", appearance,
                appearance->is_null() ? "this appearance is empty; Choreonoid ignores it"
                                      : "appearance must be a mapping; Choreonoid ignores this value",
                "indent material and texture under appearance");
    return result;
  }
  MappingReader r(ctx, appearance, "appearance");
  if (yaml::NodeRef m = r.take({"material"})) {
    if (!m->is_mapping()) {
      ctx.error("load-type", m, "material must be a mapping");
    } else {
      Material material;
      MappingReader mr(ctx, m, "material");
      set_if(material.ambient_intensity, opt_double(mr, {"ambient", "ambientIntensity"}));
      if (auto v = mr.take({"diffuse", "diffuseColor"})) set_if(material.diffuse_color, read_optional_vec3(ctx, v));
      if (auto v = mr.take({"emissive", "emissiveColor"})) set_if(material.emissive_color, read_optional_vec3(ctx, v));
      if (auto v = mr.take({"specular", "specularColor"})) set_if(material.specular_color, read_optional_vec3(ctx, v));
      if (auto v = mr.take({"specular_exponent"})) {
        set_if(material.specular_exponent, optional_double(ctx, v));
        if (auto shininess = mr.take({"shininess"}))
          ctx.warning("load-ignored-key", shininess,
                      "\"shininess\" is ignored by Choreonoid when specular_exponent is given",
                      "remove shininess");
      } else if (auto shininess = mr.take({"shininess"})) {
        // body-format-spec §8.7: legacy VRML shininess maps to an exponent.
        if (auto s = optional_double(ctx, shininess)) {
          material.specular_exponent = 127.0 * std::clamp(*s, 0.0, 1.0) + 1.0;
          ctx.note("load-legacy-key", shininess, "legacy key \"shininess\"; the modern key is \"specular_exponent\"",
                   "write specular_exponent: " + std::to_string(material.specular_exponent));
        }
      }
      set_if(material.transparency, opt_double(mr, {"transparency"}));
      mr.report_unknown({"ambient", "diffuse", "emissive", "specular", "specular_exponent",
                         "shininess", "transparency"});
      result.material = material;
    }
  }
  if (yaml::NodeRef t = r.take({"texture"})) {
    if (t->is_mapping()) {
      Texture texture;
      MappingReader tr(ctx, t, "texture");
      if (auto uri = tr.take({"uri", "url"})) {
        texture.uri = uri->scalar;
        texture.resolved_path = resolve_uri(ctx, uri, texture.uri, uri->location.file);
      }
      if (auto repeat = tr.take({"repeat"})) {
        if (repeat->is_sequence() && repeat->items.size() == 2) {
          set_if(texture.repeat_s, optional_bool(ctx, repeat->items[0]));
          set_if(texture.repeat_t, optional_bool(ctx, repeat->items[1]));
        } else if (repeat->is_scalar()) {
          auto b = optional_bool(ctx, repeat);
          set_if(texture.repeat_s, b);
          set_if(texture.repeat_t, b);
        } else {
          ctx.error("load-vector-size", repeat, "the number of the repeat elements must be two");
        }
      } else {
        set_if(texture.repeat_s, opt_bool(tr, {"repeat_s", "repeatS"}));
        set_if(texture.repeat_t, opt_bool(tr, {"repeat_t", "repeatT"}));
      }
      tr.report_unknown({"uri", "repeat", "repeat_s", "repeat_t"});
      result.texture = texture;
    } else {
      ctx.error("load-type", t, "texture must be a mapping");
    }
  }
  r.take({"texture_transform", "textureTransform"});
  r.report_unknown({"material", "texture", "texture_transform"});
  return result;
}

}  // namespace bodyfmt::detail
