// Mass properties from shapes against an independent reference (issue 39): MuJoCo 2.2.2
// computes a body's mass, centre of mass and principal moments from its geoms
// (<compiler inertiafromgeom="true">, density 1000). The MJCF is written here from the shapes
// (not by body2mjcf, whose bodies carry the written inertia): one body per link, welded to the
// world at the link frame, one geom per solid shape.
//
// Primitives (Box, Sphere, Cylinder, Capsule) are MuJoCo geoms with their closed forms in double
// precision: 1e-9 relative. Meshes: MuJoCo 2.2.2 stores mesh vertices as float and computes a
// mesh's inertia from tetrahedra between its faces and its centroid with their absolute volumes
// (what later versions call inertia="legacy"), which is exact only for meshes star-shaped about
// the centroid (every convex mesh, some others); so meshes are compared here on convex
// tessellations and on the corpus meshes star-shaped about their centroid, at 1e-5 relative
// (float vertices: ~6e-8 each, summed over the faces). And MuJoCo 2.2.2 gives
// a mesh geom the mass of its equivalent-inertia box, not of the mesh (measured: a cylinder's
// mass comes out 0.9549 of ours, which is the box's volume over the cylinder's), with the
// mesh's inertia per unit mass: so for meshes the centre of mass and the principal moments per
// unit mass are compared, and the mass with density times the equivalent box's volume.

#include <bodyfmt/derived.h>
#include <bodyfmt/geometry_mass.h>
#include <bodyfmt/inertia.h>
#include <bodyfmt/load.h>
#include <bodyfmt/tessellate.h>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <unistd.h>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace bodyfmt;

namespace {

const fs::path kCorpus = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid";
constexpr double kDensity = 1000;

std::string num(double v) { return fmt::format("{:.17g}", v); }

/// The geom of a primitive shape, or "" when the shape is no MuJoCo primitive under a rigid
/// placement (a scaled shape, a cone, a mesh).
std::string primitive_geom(const Shape& shape) {
  const Eigen::Matrix3d R = shape.X_LS.linear();
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-12 || R.determinant() < 0) return {};
  // MuJoCo's cylinder and capsule run along Z, ours along Y: turn Z onto Y (-90 degrees about X).
  const Eigen::Matrix3d z_to_y = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  std::string type, size;
  bool along_y = false;
  if (const auto* b = geometry_if<Box>(shape.geometry)) {
    if (!(b->size.minCoeff() > 0)) return {};
    type = "box", size = num(b->size.x() / 2) + " " + num(b->size.y() / 2) + " " + num(b->size.z() / 2);
  } else if (const auto* s = geometry_if<Sphere>(shape.geometry)) {
    type = "sphere", size = num(s->radius);
  } else if (const auto* c = geometry_if<Cylinder>(shape.geometry)) {
    if (!c->top || !c->bottom) return {};
    type = "cylinder", size = num(c->radius) + " " + num(c->height / 2), along_y = true;
  } else if (const auto* c = geometry_if<Capsule>(shape.geometry)) {
    if (!(c->height > 0)) return {};
    type = "capsule", size = num(c->radius) + " " + num(c->height / 2), along_y = true;
  } else {
    return {};
  }
  const Eigen::Quaterniond q(along_y ? Eigen::Matrix3d(R * z_to_y) : R);
  const Eigen::Vector3d p = shape.X_LS.translation();
  return fmt::format(R"(<geom type="{}" size="{}" pos="{} {} {}" quat="{} {} {} {}" density="{}"/>)", type, size,
                     num(p.x()), num(p.y()), num(p.z()), num(q.w()), num(q.x()), num(q.y()), num(q.z()), kDensity);
}

struct Compiled {
  mjModel* m = nullptr;
  std::string error;
  explicit Compiled(const fs::path& xml) {
    char err[1000] = "";
    m = mj_loadXML(xml.string().c_str(), nullptr, err, sizeof err);
    error = err;
  }
  ~Compiled() {
    if (m) mj_deleteModel(m);
  }
  Compiled(const Compiled&) = delete;
  Compiled& operator=(const Compiled&) = delete;
};

/// Our link mass at kDensity against MuJoCo's body `b`.
/// For a mesh (`per_unit_mass`), the moments are compared per unit mass and the mass with that
/// of the equivalent-inertia box (module comment).
void compare(const mjModel* m, int b, const MassProperties& ours, double tolerance, const std::string& what,
             bool per_unit_mass = false) {
  INFO(what);
  const double mass = m->body_mass[b];
  const Eigen::Vector3d moments = principal_inertia(ours.inertia).moments;
  double expected_mass = ours.mass;
  if (per_unit_mass) {
    // Box edges from I_i = m (e_j² + e_k²) / 12: e_i² = 6 (I_j + I_k - I_i) / m.
    const Eigen::Vector3d& I = moments;
    const double box = std::sqrt(6 * (I[1] + I[2] - I[0]) / ours.mass) *
                       std::sqrt(6 * (I[0] + I[2] - I[1]) / ours.mass) *
                       std::sqrt(6 * (I[0] + I[1] - I[2]) / ours.mass);
    expected_mass = kDensity * box;
  }
  CHECK(std::abs(mass - expected_mass) <= tolerance * expected_mass);
  const Eigen::Vector3d com(m->body_ipos[3 * b], m->body_ipos[3 * b + 1], m->body_ipos[3 * b + 2]);
  const double length = std::sqrt(ours.inertia.trace() / ours.mass);  // the body's radius of gyration
  CHECK((com - ours.center_of_mass).norm() <= tolerance * std::max(length, ours.center_of_mass.norm()));
  Eigen::Vector3d theirs(m->body_inertia[3 * b], m->body_inertia[3 * b + 1], m->body_inertia[3 * b + 2]);
  std::sort(theirs.data(), theirs.data() + 3);
  const Eigen::Vector3d compared = per_unit_mass ? Eigen::Vector3d(moments / ours.mass) : moments;
  if (per_unit_mass) theirs /= mass;
  INFO("MuJoCo " << theirs.transpose() << ", ours " << compared.transpose());
  CHECK((theirs - compared).cwiseAbs().maxCoeff() <= tolerance * compared.maxCoeff());
}

fs::path temp_xml(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("bodyfmt-geometry-mass-{}", ::getpid());
  fs::create_directories(dir);
  return dir / name;
}

}  // namespace

TEST_CASE("geometry mass: every corpus link of primitives matches MuJoCo's inertiafromgeom to 1e-9") {
  int compared = 0, links_with_meshes = 0, models = 0;
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(kCorpus))
    if (entry.path().extension() == ".body") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 50);
  for (const fs::path& file : files) {
    CollectingSink sink;
    const std::optional<Model> model = load_body(file.string(), LoadOptions{}, sink);
    if (!model) continue;
    ++models;
    std::string bodies;
    std::vector<std::pair<std::size_t, MassProperties>> expected;
    for (std::size_t i = 0; i < model->links.size(); ++i) {
      const Link& link = model->links[i];
      const LinkGeometryMass g = link_geometry_mass(*model, link, sink);
      if (g.empty()) continue;
      std::string geoms;
      bool all_primitive = g.left_out == 0;
      for (const Shape& shape : link.shapes) {
        if (!(g.from_visual ? shape.visual : shape.collision)) continue;
        const std::string geom = primitive_geom(shape);
        all_primitive = all_primitive && !geom.empty();
        geoms += geom;
      }
      if (!all_primitive) {
        ++links_with_meshes;
        continue;
      }
      bodies += fmt::format(R"(<body name="L{}">{}</body>)", i, geoms);
      expected.emplace_back(i, at_density(g.volume, kDensity));
    }
    if (expected.empty()) continue;
    const fs::path xml = temp_xml("links.xml");
    std::ofstream(xml) << R"(<mujoco><compiler angle="radian" inertiafromgeom="true"/><worldbody>)" << bodies
                       << "</worldbody></mujoco>\n";
    const Compiled compiled(xml);
    INFO(file.string() << ": " << compiled.error);
    REQUIRE(compiled.m);
    for (const auto& [link, ours] : expected) {
      const int b = mj_name2id(compiled.m, mjOBJ_BODY, fmt::format("L{}", link).c_str());
      REQUIRE(b > 0);
      compare(compiled.m, b, ours, 1e-9, fmt::format("{} link {}", file.filename().string(), model->links[link].name));
      ++compared;
    }
  }
  MESSAGE(fmt::format("{} models, {} links of primitives compared, {} links with meshes left to the mesh case", models,
                      compared, links_with_meshes));
  CHECK(compared >= 100);
}

TEST_CASE("geometry mass: convex tessellated meshes match MuJoCo's mesh inertia to float accuracy") {
  // A cone, a cylinder and an extrusion (a square prism sheared along its spine is still convex),
  // placed off the origin and rotated: the mesh as the tessellator makes it, written as a
  // MuJoCo mesh in the body frame.
  Cone cone;
  cone.radius = 0.07;
  cone.height = 0.2;
  Cylinder cylinder;
  cylinder.radius = 0.05;
  cylinder.height = 0.3;
  Extrusion prism;
  prism.cross_section = {{-0.1, -0.1}, {-0.1, 0.1}, {0.1, 0.1}, {0.1, -0.1}, {-0.1, -0.1}};
  prism.spine = {{0, 0, 0}, {0.02, 0.3, 0.01}};
  prism.scale = {{1, 1}};
  prism.orientation = {Eigen::AngleAxisd(0, Eigen::Vector3d::UnitZ())};
  int k = 0;
  for (const Geometry& g : {Geometry(cone), Geometry(cylinder), Geometry(HeapValue<Extrusion>(prism))}) {
    CollectingSink sink;
    Eigen::Affine3d X = Eigen::Affine3d::Identity();
    X.translate(Eigen::Vector3d(0.3, -0.1, 0.7));
    X.rotate(Eigen::AngleAxisd(0.4 + k, Eigen::Vector3d(1, -2, 0.5).normalized()));
    TriangleMesh placed;
    append_mesh(placed, tessellate(g, 48, sink, SourceLocation{}), X);
    REQUIRE(mesh_solidity(placed).solid());
    std::string vertex, face;
    for (const Eigen::Vector3d& v : placed.vertices)
      vertex += fmt::format("{} {} {} ", num(v.x()), num(v.y()), num(v.z()));
    for (const auto& t : placed.triangles) face += fmt::format("{} {} {} ", t[0], t[1], t[2]);
    const fs::path xml = temp_xml(fmt::format("mesh{}.xml", k));
    std::ofstream(xml) << R"(<mujoco><compiler angle="radian" inertiafromgeom="true"/><asset><mesh name="m" vertex=")"
                       << vertex << R"(" face=")" << face
                       << R"("/></asset><worldbody><body name="B"><geom type="mesh" mesh="m" density="1000"/></body>)"
                       << "</worldbody></mujoco>\n";
    const Compiled compiled(xml);
    INFO("geometry " << g.index() << ": " << compiled.error);
    REQUIRE(compiled.m);
    compare(compiled.m, 1, at_density(mesh_mass_properties(placed), kDensity), 1e-5, "tessellated mesh", true);
    ++k;
  }
}

namespace {

/// Whether every vertex lies on the inner side of every face's plane (to `slack`).
bool convex(const TriangleMesh& mesh, double slack) {
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    if (n.norm() == 0) continue;
    const Eigen::Vector3d u = n.normalized();
    for (const Eigen::Vector3d& v : mesh.vertices)
      if (u.dot(v - a) > slack) return false;
  }
  return true;
}

/// Whether every face sees `centre` from its inner side: the tetrahedra between the faces and
/// the centre then all have positive volume, and summing their absolute volumes (MuJoCo 2.2.2)
/// is the divergence theorem.
bool star_shaped_about(const TriangleMesh& mesh, const Eigen::Vector3d& centre, double volume) {
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]] - centre, b = mesh.vertices[t[1]] - centre,
                          c = mesh.vertices[t[2]] - centre;
    if (a.dot(b.cross(c)) / 6 < -1e-12 * volume) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("geometry mass: corpus meshes star-shaped about their centroid, convex or not, match MuJoCo 2.2.2 to 1e-5") {
  // MuJoCo 2.2.2 sums each face's tetrahedron with the mesh's centre by its absolute volume. That
  // is the divergence theorem exactly when every tetrahedron's volume is positive: the mesh is
  // star-shaped about the centre, which every convex mesh is and some non-convex ones are. For
  // the others it counts the volume outside a concavity twice (on the corpus, 1.005 to 16.7
  // times the enclosed volume) and is no reference: those are counted, not compared. 1e-5 as for
  // the tessellated meshes: MuJoCo holds mesh vertices as float.
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(kCorpus))
    if (entry.path().extension() == ".body") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::set<std::string> seen;
  int convex_compared = 0, non_convex_compared = 0, not_star_shaped = 0, refused = 0;
  for (const fs::path& file : files) {
    CollectingSink sink;
    const std::optional<Model> model = load_body(file.string(), LoadOptions{}, sink);
    if (!model) continue;
    for (const Link& link : model->links) {
      for (const Shape& shape : link.shapes) {
        const auto* resource = geometry_if<MeshResource>(shape.geometry);
        if (!resource || !seen.insert(file.parent_path().string() + "/" + resource->uri).second) continue;
        const TriangleMesh local = compute_shape_local_mesh(*model, shape, sink);
        if (local.empty() || !mesh_solidity(local).solid()) continue;
        const MassProperties ours = mesh_mass_properties(local);
        if (!(ours.mass > 0)) continue;
        if (!star_shaped_about(local, ours.center_of_mass, ours.mass)) {
          ++not_star_shaped;
          continue;
        }
        std::string vertex, face;
        for (const Eigen::Vector3d& v : local.vertices)
          vertex += fmt::format("{} {} {} ", num(v.x()), num(v.y()), num(v.z()));
        for (const auto& t : local.triangles) face += fmt::format("{} {} {} ", t[0], t[1], t[2]);
        const fs::path xml = temp_xml("corpus_mesh.xml");
        std::ofstream(xml)
            << R"(<mujoco><compiler angle="radian" inertiafromgeom="true"/><asset><mesh name="m" vertex=")" << vertex
            << R"(" face=")" << face
            << R"("/></asset><worldbody><body name="B"><geom type="mesh" mesh="m" density="1000"/></body>)"
            << "</worldbody></mujoco>\n";
        const Compiled compiled(xml);
        if (!compiled.m) {  // MuJoCo 2.2.2 reads orientation by vertex index, not position
          MESSAGE(fmt::format("{}: MuJoCo refuses {}: {}", file.filename().string(), resource->uri, compiled.error));
          ++refused;
          continue;
        }
        const bool is_convex = convex(local, 1e-9 * std::cbrt(ours.mass));
        ++(is_convex ? convex_compared : non_convex_compared);
        compare(compiled.m, 1, at_density(ours, kDensity), 1e-5,
                fmt::format("{} {} ({} triangles, {})", file.filename().string(), resource->uri, local.triangles.size(),
                            is_convex ? "convex" : "not convex"),
                true);
      }
    }
  }
  MESSAGE(
      fmt::format("corpus meshes compared with MuJoCo: {} convex, {} not convex but star-shaped; {} not "
                  "star-shaped (no reference), {} refused by MuJoCo",
                  convex_compared, non_convex_compared, not_star_shaped, refused));
  CHECK(convex_compared >= 5);
  CHECK(non_convex_compared >= 2);
}
