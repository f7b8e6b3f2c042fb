// Texture coordinates of tessellate(..., TexCoords::kGenerate). Expected values are derived by
// hand from the conventions (Choreonoid's MeshGenerator, VRML97), written out in comments, and
// looked up by corner position, so they do not depend on the vertex order.
#include <bodyfmt/tessellate.h>
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <set>
#include <utility>

using namespace bodyfmt;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

const SourceLocation kWhere{"robot.body", 3, 5};

TriangleMesh textured(const Geometry& geometry, int division = 20) {
  CollectingSink sink;
  TriangleMesh m = tessellate(geometry, division, sink, kWhere, TexCoords::kGenerate);
  CHECK(sink.diagnostics().empty());
  return m;
}

Vector3d normal_of(const TriangleMesh& m, const std::array<int, 3>& t) {
  const Vector3d& a = m.vertices[static_cast<std::size_t>(t[0])];
  return (m.vertices[static_cast<std::size_t>(t[1])] - a).cross(m.vertices[static_cast<std::size_t>(t[2])] - a);
}

const Vector3d& at(const TriangleMesh& m, int v) { return m.vertices[static_cast<std::size_t>(v)]; }
const Vector2d& uv(const TriangleMesh& m, int v) { return m.tex_coords[static_cast<std::size_t>(v)]; }

bool near(const Vector3d& a, const Vector3d& b) { return (a - b).norm() < 1e-9; }

}  // namespace

TEST_CASE("tex coords: untextured tessellation has none, textured has one per vertex") {
  CollectingSink sink;
  const Box box{Vector3d(1, 2, 3)};
  const TriangleMesh plain = tessellate(box, 20, sink, kWhere);
  CHECK(plain.tex_coords.empty());
  CHECK(plain.vertices.size() == 8);
  const TriangleMesh uv_mesh = textured(box);
  CHECK(uv_mesh.tex_coords.size() == uv_mesh.vertices.size());
  // Same surface: the triangles are kept in order, only the vertices are split.
  REQUIRE(uv_mesh.triangles.size() == plain.triangles.size());
  for (std::size_t t = 0; t < plain.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k)
      CHECK(near(at(uv_mesh, uv_mesh.triangles[t][k]), at(plain, plain.triangles[t][k])));
  CHECK(signed_volume(uv_mesh) == doctest::Approx(6.0).epsilon(1e-14));
}

TEST_CASE("tex coords: every box face maps the whole image, upright seen from outside") {
  // Box 2 x 4 x 6: corners at (+-1, +-2, +-3). The expected (u, v) of each face's four corners
  // follow from Choreonoid's generateTextureCoordinateForBox (texCoords (0,0) (1,0) (0,1) (1,1)
  // indexed per triangle corner): e.g. its first triangle {0,1,2} = (x,y,z) (-x,y,z) (-x,-y,z)
  // has texCoordIndices 3,2,0, i.e. (1,1) (0,1) (0,0): on +Z, u grows with x and v with y.
  struct Corner {
    Vector3d p;
    Vector2d uv;
  };
  const std::map<std::string, std::vector<Corner>> faces = {
      {"+Z", {{{1, 2, 3}, {1, 1}}, {{-1, 2, 3}, {0, 1}}, {{-1, -2, 3}, {0, 0}}, {{1, -2, 3}, {1, 0}}}},
      // top: triangles {0,5,1} {0,4,5} with indices 1,2,0 / 1,3,2: u with +x, v with -z
      {"+Y", {{{1, 2, 3}, {1, 0}}, {{-1, 2, -3}, {0, 1}}, {{-1, 2, 3}, {0, 0}}, {{1, 2, -3}, {1, 1}}}},
      // {1,5,6} {1,6,2} with 3,2,0 / 3,0,1: u with +z, v with y
      {"-X", {{{-1, 2, 3}, {1, 1}}, {{-1, 2, -3}, {0, 1}}, {{-1, -2, -3}, {0, 0}}, {{-1, -2, 3}, {1, 0}}}},
      // bottom: {2,6,7} {2,7,3} with 2,0,1 / 2,1,3: u with +x, v with +z
      {"-Y", {{{-1, -2, 3}, {0, 1}}, {{-1, -2, -3}, {0, 0}}, {{1, -2, -3}, {1, 0}}, {{1, -2, 3}, {1, 1}}}},
      // {3,7,4} {3,4,0} with 0,1,3 / 0,3,2: u with -z, v with y
      {"+X", {{{1, -2, 3}, {0, 0}}, {{1, -2, -3}, {1, 0}}, {{1, 2, -3}, {1, 1}}, {{1, 2, 3}, {0, 1}}}},
      // back: {4,6,5} {4,7,6} with 2,1,3 / 2,0,1: u with -x, v with y
      {"-Z", {{{1, 2, -3}, {0, 1}}, {{-1, -2, -3}, {1, 0}}, {{-1, 2, -3}, {1, 1}}, {{1, -2, -3}, {0, 0}}}},
  };
  const TriangleMesh m = textured(Box{Vector3d(2, 4, 6)});
  // A corner is one vertex per distinct (u, v) among its three faces: the four corners at
  // z = +3 have three, the four at z = -3 two (from the table: (1, 2, -3) is (1, 1) on +Y and
  // +X), so 4 x 3 + 4 x 2.
  CHECK(m.vertices.size() == 20);
  REQUIRE(m.triangles.size() == 12);
  std::set<std::string> seen;
  for (const auto& t : m.triangles) {
    const Vector3d n = normal_of(m, t).normalized();
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    const std::string face = std::string(n[axis] > 0 ? "+" : "-") + "XYZ"[axis];
    seen.insert(face);
    for (int v : t) {
      bool found = false;
      for (const Corner& c : faces.at(face)) {
        if (!near(c.p, at(m, v))) continue;
        found = true;
        CHECK_MESSAGE(uv(m, v).isApprox(c.uv, 1e-12), face, " corner ", at(m, v).transpose());
      }
      CHECK(found);
    }
  }
  CHECK(seen.size() == 6);
}

TEST_CASE("tex coords: cylinder side runs u from -Z around Y, caps are inscribed discs") {
  // n = 8, radius 1, height 2: ring vertex j at angle 2 pi j / 8 from +X towards +Z.
  // Side u = (atan2(x, z) + pi) / (2 pi) (Choreonoid's formula): +X -> (pi/2 + pi) / 2pi = 0.75,
  // +Z -> 0.5, -X -> 0.25, (0.7071, 0.7071) -> (pi/4 + pi) / 2pi = 0.625, -Z -> 0 or 1 (the
  // seam). v = 1 at the top rim, 0 at the bottom rim.
  // Top cap: (0.5 + 0.5 cos a, 0.5 - 0.5 sin a): +X -> (1, 0.5), +Z -> (0.5, 0), -X -> (0, 0.5),
  // -Z -> (0.5, 1); bottom cap mirrors v: +Z -> (0.5, 1), -Z -> (0.5, 0). Centres (0.5, 0.5).
  const double s = std::sqrt(0.5);
  const std::vector<std::pair<Vector3d, double>> side_u = {
      {{1, 0, 0}, 0.75},  {{s, 0, s}, 0.625},   {{0, 0, 1}, 0.5},   {{-s, 0, s}, 0.375},
      {{-1, 0, 0}, 0.25}, {{-s, 0, -s}, 0.125}, {{s, 0, -s}, 0.875}};
  const TriangleMesh m = textured(Cylinder{1, 2, true, true}, 8);
  // Side: 2 rings of 8 plus the seam copies at -Z (u = 0 and 1); caps: 8 + centre each.
  CHECK(m.vertices.size() == 18 + 18);
  int side_corners = 0, seam_corners = 0, cap_corners = 0;
  for (const auto& t : m.triangles) {
    const Vector3d n = normal_of(m, t).normalized();
    for (int v : t) {
      const Vector3d p = at(m, v);
      const Vector2d& c = uv(m, v);
      if (std::abs(n.y()) < 0.5) {
        ++side_corners;
        CHECK(c.y() == (p.y() > 0 ? 1.0 : 0.0));
        const Vector3d flat(p.x(), 0, p.z());
        if (near(flat, Vector3d(0, 0, -1))) {
          ++seam_corners;
          // The triangle's other corners decide: beside -X's side (u 0.125) it is 0, beside +X's (0.875) 1.
          double other = 0;
          for (int w : t)
            if (!near(Vector3d(at(m, w).x(), 0, at(m, w).z()), flat)) other = uv(m, w).x();
          CHECK(c.x() == (other > 0.5 ? 1.0 : 0.0));
        } else {
          bool found = false;
          for (const auto& [q, u] : side_u) {
            if (!near(q, flat)) continue;
            found = true;
            CHECK(c.x() == doctest::Approx(u).epsilon(1e-12));
          }
          CHECK(found);
        }
      } else {
        ++cap_corners;
        const bool top = n.y() > 0;
        Vector2d expected(0.5, 0.5);
        if (near(Vector3d(p.x(), 0, p.z()), Vector3d(1, 0, 0))) expected = {1, 0.5};
        if (near(Vector3d(p.x(), 0, p.z()), Vector3d(0, 0, 1))) expected = {0.5, top ? 0 : 1};
        if (near(Vector3d(p.x(), 0, p.z()), Vector3d(-1, 0, 0))) expected = {0, 0.5};
        if (near(Vector3d(p.x(), 0, p.z()), Vector3d(0, 0, -1))) expected = {0.5, top ? 1 : 0};
        if (near(Vector3d(p.x(), 0, p.z()), Vector3d(s, 0, s)))
          expected = {0.5 + 0.5 * s, top ? 0.5 - 0.5 * s : 0.5 + 0.5 * s};
        if (expected != Vector2d(0.5, 0.5) || near(Vector3d(p.x(), 0, p.z()), Vector3d::Zero()))
          CHECK_MESSAGE(c.isApprox(expected, 1e-12), p.transpose(), " -> ", c.transpose());
      }
    }
  }
  CHECK(side_corners == 16 * 3);
  CHECK(seam_corners == 6);  // two triangles on each side of the seam use a -Z corner, 2 + 1 each
  CHECK(cap_corners == 16 * 3);
}

TEST_CASE("tex coords: with_vertex_normals smooths across the texture seam") {
  // Shading must not see the texture seam: every side vertex of the textured cylinder gets the
  // normal the untextured one has at that position. Split by index alone, each seam copy at -Z
  // would average only the faces on its own side and tilt by about half a facet.
  CollectingSink sink;
  const TriangleMesh plain = with_vertex_normals(tessellate(Cylinder{1, 2, true, true}, 8, sink, kWhere), 1.0);
  const TriangleMesh m = with_vertex_normals(textured(Cylinder{1, 2, true, true}, 8), 1.0);
  REQUIRE(m.tex_coords.size() == m.vertices.size());
  int side_vertices = 0, seam_vertices = 0;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    if (m.normals[v].y() != 0) continue;  // cap vertices
    ++side_vertices;
    const Vector3d& p = m.vertices[v];
    if (near(Vector3d(p.x(), 0, p.z()), Vector3d(0, 0, -1))) ++seam_vertices;
    for (std::size_t w = 0; w < plain.vertices.size(); ++w) {
      if (near(plain.vertices[w], p) && plain.normals[w].y() == 0)
        CHECK_MESSAGE(m.normals[v].isApprox(plain.normals[w], 1e-12), p.transpose());
    }
  }
  CHECK(side_vertices == 18);
  CHECK(seam_vertices == 4);  // u 0 and 1, top and bottom rim
}

TEST_CASE("tex coords: sphere latitude and longitude, pole corners centred") {
  // n = 8: 4 bands, rings at polar angle pi/4, pi/2, 3pi/4 -> v = 1 - angle / pi = 0.75, 0.5,
  // 0.25; the top pole v = 1, the bottom 0. A top-pole corner takes the mean u of its two
  // ring neighbours: between +X (0.75) and (s, s) (0.625) that is 0.6875.
  const TriangleMesh m = textured(Sphere{1}, 8);
  const double s = std::sqrt(0.5);
  int checked = 0;
  for (const auto& t : m.triangles) {
    for (int v : t) {
      const Vector3d& p = at(m, v);
      if (std::abs(p.y() - s) < 1e-9) CHECK(uv(m, v).y() == doctest::Approx(0.75));
      if (std::abs(p.y()) < 1e-9) CHECK(uv(m, v).y() == doctest::Approx(0.5));
      if (std::abs(p.y() + s) < 1e-9) CHECK(uv(m, v).y() == doctest::Approx(0.25));
      if (near(p, Vector3d(0, 1, 0))) CHECK(uv(m, v).y() == 1.0);
      if (near(p, Vector3d(0, -1, 0))) CHECK(uv(m, v).y() == 0.0);
    }
    std::vector<Vector3d> ps;
    for (int v : t) ps.push_back(at(m, v));
    for (int k = 0; k < 3; ++k) {
      if (!near(ps[static_cast<std::size_t>(k)], Vector3d(0, 1, 0))) continue;
      const Vector3d a = ps[static_cast<std::size_t>((k + 1) % 3)], b = ps[static_cast<std::size_t>((k + 2) % 3)];
      const Vector3d x_ring(s, s, 0), diagonal(0.5, s, 0.5);
      if ((near(a, x_ring) && near(b, diagonal)) || (near(b, x_ring) && near(a, diagonal))) {
        CHECK(uv(m, t[static_cast<std::size_t>(k)]).x() == doctest::Approx(0.6875));
        ++checked;
      }
    }
  }
  CHECK(checked == 1);
  CHECK(signed_volume(m) > 0);
}

TEST_CASE("tex coords: indexed face set uses its texCoordIndex and splits a seam") {
  // Two unit quads side by side in z = 0 sharing the edge x = 1. The left quad's corners take
  // tex_coords 0..3 through texCoordIndex, the right one's 6, 4, 5, 7: the shared corner
  // (1, 0, 0) is (0.5, 0) on the left and (0.25, 0) on the right, so it is split.
  IndexedFaceSet f;
  f.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  f.faces = {0, 1, 2, 3, -1, 1, 4, 5, 2, -1};
  f.tex_coords = {{0, 0}, {0.5, 0}, {0.5, 1}, {0, 1}, {1, 0}, {1, 1}, {0.25, 0}, {0.25, 1}};
  f.tex_coord_indices = {0, 1, 2, 3, -1, 6, 4, 5, 7, -1};
  const TriangleMesh m = textured(f);
  REQUIRE(m.triangles.size() == 4);
  CHECK(m.vertices.size() == 8);
  const std::map<std::pair<bool, std::pair<double, double>>, Vector2d> expected = {
      // (right quad?, (x, y)) -> (u, v): the texture points named by texCoordIndex.
      {{false, {0, 0}}, {0, 0}}, {{false, {1, 0}}, {0.5, 0}}, {{false, {1, 1}}, {0.5, 1}},
      {{false, {0, 1}}, {0, 1}}, {{true, {1, 0}}, {0.25, 0}}, {{true, {2, 0}}, {1, 0}},
      {{true, {2, 1}}, {1, 1}},  {{true, {1, 1}}, {0.25, 1}}};
  for (const auto& t : m.triangles) {
    const bool right = (at(m, t[0]).x() + at(m, t[1]).x() + at(m, t[2]).x()) / 3 > 1;
    for (int v : t) CHECK(uv(m, v) == expected.at({right, {at(m, v).x(), at(m, v).y()}}));
  }

  // Without texCoordIndex, coordIndex picks the texture points: vertex i -> tex_coords[i].
  f.tex_coord_indices.clear();
  const TriangleMesh by_vertex = textured(f);
  CHECK(by_vertex.vertices.size() == 6);
  for (std::size_t v = 0; v < by_vertex.vertices.size(); ++v) {
    if (near(by_vertex.vertices[v], Vector3d(2, 1, 0))) CHECK(by_vertex.tex_coords[v] == Vector2d(1, 1));
    if (near(by_vertex.vertices[v], Vector3d(1, 0, 0))) CHECK(by_vertex.tex_coords[v] == Vector2d(0.5, 0));
  }

  // An index past the texture points gives no texture coordinates at all (the exporter then
  // reports the texture as lost) rather than made-up ones.
  f.tex_coord_indices = {0, 1, 2, 3, -1, 6, 4, 5, 8, -1};
  CHECK(textured(f).tex_coords.empty());
}

TEST_CASE("tex coords: face sets without texCoord project onto the two largest extents") {
  // VRML97 default: bounding box 2 (x) by 1 (y) by 0 (z): u = x / 2 along the largest extent,
  // v = y / 2 along the second at the same scale, so (2, 1, 0) -> (1, 0.5).
  IndexedFaceSet f;
  f.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  f.faces = {0, 1, 2, 3, -1, 1, 4, 5, 2, -1};
  const TriangleMesh m = textured(f);
  CHECK(m.vertices.size() == 6);
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    CHECK(m.tex_coords[v].isApprox(Vector2d(m.vertices[v].x() / 2, m.vertices[v].y() / 2), 1e-15));

  // Standing in the y-z plane, taller than wide: y (3) is the largest, z (1) the second.
  TriangleMeshGeometry g;
  g.vertices = {{5, 0, 0}, {5, 3, 0}, {5, 0, 1}};
  g.faces = {0, 1, 2};
  const TriangleMesh tri = textured(g);
  for (std::size_t v = 0; v < tri.vertices.size(); ++v)
    CHECK(tri.tex_coords[v].isApprox(Vector2d(tri.vertices[v].y() / 3, tri.vertices[v].z() / 3), 1e-15));
}

TEST_CASE("tex coords: elevation grid u along x, v along z, cone apex and base") {
  // 3 x 2 points: u = i / 2, v = j / 1.
  ElevationGrid grid;
  grid.x_dimension = 3;
  grid.z_dimension = 2;
  grid.x_spacing = 0.5;
  grid.z_spacing = 4;
  grid.height = {0, 1, 0, 0, 2, 0};
  const TriangleMesh m = textured(grid);
  CHECK(m.vertices.size() == 6);
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    CHECK(m.tex_coords[v].isApprox(Vector2d(m.vertices[v].x() / 1.0, m.vertices[v].z() / 4), 1e-15));

  // Cone, n = 4: base corners +X (u 0.75), +Z (0.5), -X (0.25), -Z (0 / 1) at v = 0; the apex
  // (v = 1) of the face between +X and +Z at their mean u, 0.625; base disc as the bottom cap:
  // +Z -> (0.5, 1).
  const TriangleMesh cone = textured(Cone{1, 2, true}, 4);
  int apexes = 0;
  for (const auto& t : cone.triangles) {
    std::set<std::pair<long, long>> xz;
    for (int v : t) xz.insert({std::lround(at(cone, v).x()), std::lround(at(cone, v).z())});
    for (int v : t) {
      if (at(cone, v).y() > 0 && xz.count({1, 0}) && xz.count({0, 1})) {
        CHECK(uv(cone, v) == Vector2d(0.625, 1));
        ++apexes;
      }
      if (normal_of(cone, t).y() < 0 && near(at(cone, v), Vector3d(0, -1, 1)))
        CHECK(uv(cone, v).isApprox(Vector2d(0.5, 1)));
    }
  }
  CHECK(apexes == 1);
}

TEST_CASE("tex coords: extrusion sides by length along cross-section and spine, caps by its box") {
  // A 2 x 2 square cross-section (closed: the first point repeats) swept from y = 0 to 1 up +Y,
  // so cross-section point (x, z) sits at (x, y, z). Sides: the perimeter is 8 in four edges of
  // 2, so u = 0, 0.25, 0.5, 0.75 at (1, 1), (1, -1), (-1, -1), (-1, 1) and 1 where the last edge
  // closes at (1, 1); v = y. Caps: the cross-section's box [-1, 1]^2 stretched to the image:
  // begin cap (y = 0) ((x + 1) / 2, (z + 1) / 2), end cap (y = 1) mirrored in u.
  Extrusion e;
  e.cross_section = {{1, 1}, {1, -1}, {-1, -1}, {-1, 1}, {1, 1}};
  e.spine = {{0, 0, 0}, {0, 1, 0}};
  const TriangleMesh m = textured(e);
  REQUIRE(m.triangles.size() == 12);
  REQUIRE(m.tex_coords.size() == m.vertices.size());
  // Sides: 2 rows x (4 + the seam copy); caps: 4 each; less one, as corner (1, 1) at y = 1 is
  // (0, 1) both on the side and on the end cap (1 - (1 + 1) / 2 = 0, (1 + 1) / 2 = 1).
  CHECK(m.vertices.size() == 10 + 8 - 1);
  const std::map<std::pair<long, long>, double> side_u = {{{1, -1}, 0.25}, {{-1, -1}, 0.5}, {{-1, 1}, 0.75}};
  int side = 0, caps = 0;
  for (const auto& t : m.triangles) {
    const Vector3d n = normal_of(m, t);
    std::set<std::pair<long, long>> xz;
    for (int v : t) xz.insert({std::lround(at(m, v).x()), std::lround(at(m, v).z())});
    for (int v : t) {
      const Vector3d& p = at(m, v);
      const std::pair<long, long> key{std::lround(p.x()), std::lround(p.z())};
      Vector2d expected;
      if (std::abs(n.y()) < 1e-9) {
        ++side;
        // (1, 1) is u 0 on the first edge, 1 on the closing edge from (-1, 1).
        const double u = side_u.count(key) ? side_u.at(key) : (xz.count({-1, 1}) ? 1.0 : 0.0);
        expected = {u, p.y()};
      } else {
        ++caps;
        const double u = (p.x() + 1) / 2;
        expected = {p.y() < 0.5 ? u : 1 - u, (p.z() + 1) / 2};
      }
      CHECK_MESSAGE(uv(m, v).isApprox(expected, 1e-12), p.transpose(), " -> ", uv(m, v).transpose());
    }
  }
  CHECK(side == 8 * 3);
  CHECK(caps == 4 * 3);
}

TEST_CASE("tex coords: a capsule runs v over its whole height") {
  // Capsule radius 1, height 2: from y = -2 to 2, so v = (y + 2) / 4.
  const TriangleMesh m = textured(Capsule{1, 2}, 8);
  REQUIRE(m.tex_coords.size() == m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    CHECK(m.tex_coords[v].y() == doctest::Approx((m.vertices[v].y() + 2) / 4).epsilon(1e-12));
}
