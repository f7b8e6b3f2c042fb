// Loader unit tests for load/geometry.cpp: geometry keys of every type, appearance and
// texture (body-format-spec §8.6, §8.7, §9). load_v2 writes lines 1-2; "links:" is line 3,
// "  - name: A" line 4, "    elements:" line 5, so the first element starts on line 6.

#include "support/load_helpers.h"

#include <bodyfmt/angles.h>

#include <cmath>

using namespace bodyfmt;
using bodyfmt::test::load_v2;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

namespace {
using bodyfmt::kPi;
}  // namespace

TEST_CASE("load: Box, Sphere, Cylinder, Cone and Capsule keys") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - {type: Shape, geometry: {type: Box, size: [0.45, 0.3, 0.1]}}
      - {type: Shape, geometry: {type: Sphere, radius: 0.25}}
      - {type: Shape, geometry: {type: Cylinder, radius: 0.1, height: 0.2, top: false, division_number: 36}}
      - {type: Shape, geometry: {type: Cone, radius: 0.3, height: 0.4, bottom: false}}
      - {type: Shape, geometry: {type: Capsule, radius: 0.05, height: 0}}
      - {type: Shape, geometry: {type: Box}}
)");
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 6);
  CHECK(std::get<Box>(s[0].geometry).size == Eigen::Vector3d(0.45, 0.3, 0.1));
  CHECK(std::get<Sphere>(s[1].geometry).radius == 0.25);
  const auto& cyl = std::get<Cylinder>(s[2].geometry);
  CHECK(cyl.radius == 0.1);
  CHECK(cyl.height == 0.2);
  CHECK_FALSE(cyl.top);
  CHECK(cyl.bottom);
  CHECK(s[2].division_number == 36);
  const auto& cone = std::get<Cone>(s[3].geometry);
  CHECK(cone.radius == 0.3);
  CHECK(cone.height == 0.4);
  CHECK_FALSE(cone.bottom);
  const auto& cap = std::get<Capsule>(s[4].geometry);
  CHECK(cap.radius == 0.05);
  CHECK(cap.height == 0);  // height 0 is allowed
  CHECK(std::get<Box>(s[5].geometry).size == Eigen::Vector3d(1, 1, 1));
  CHECK(s[5].division_number == 20);
  r.expect_clean();
}

TEST_CASE("load: size: 1 on a Box is ignored and gives the default 1x1x1") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Box, size: 1}
)");
  // "        geometry: {type: Box, size: " is 36 characters.
  auto d = r.take("load-ignored-value");
  CHECK(d.severity == Severity::kWarning);
  CHECK(pos(d) == Pos{7, 37});
  CHECK(std::get<Box>(r.link("A").shapes.at(0).geometry).size == Eigen::Vector3d(1, 1, 1));
  r.expect_clean();
}

TEST_CASE("load: non-positive primitive sizes are geometry-invalid-size") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Sphere, radius: 0}
      - type: Shape
        geometry: {type: Box, size: [1, -1, 1]}
      - type: Shape
        geometry: {type: Capsule, height: -1}
)");
  CHECK(pos(r.take("geometry-invalid-size")) == Pos{7, 42});
  CHECK(pos(r.take("geometry-invalid-size")) == Pos{9, 37});
  CHECK(pos(r.take("geometry-invalid-size")) == Pos{11, 43});
  r.expect_clean();
}

TEST_CASE("load: unknown geometry type is geometry-unknown-type with did-you-mean") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Cylindre}
)");
  auto d = r.take("geometry-unknown-type");
  CHECK(pos(d) == Pos{7, 26});
  CHECK(d.fix_hint.find("Cylinder") != std::string::npos);
  CHECK(r.link("A").shapes.empty());
  r.expect_clean();
}

TEST_CASE("load: Extrusion keys, beginCap works, begin_cap is ignored with a warning") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry:
          type: Extrusion
          cross_section: [-0.22, -0.1, 0.22, -0.1, 0.34, 0.06, -0.34, 0.06, -0.22, -0.1]
          spine: [0, -0.05, 0, 0, 0.05, 0]
          orientation: [0, 1, 0, 90]
          scale: [1, 2]
          crease_angle: 30
          beginCap: false
          endCap: false
      - type: Shape
        geometry:
          type: Extrusion
          crossSection: [0, 0, 1, 0, 1, 1]
          spine: [0, 0, 0, 0, 1, 0]
          begin_cap: false
)");
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 2);
  const auto& e = geometry_get<Extrusion>(s[0].geometry);
  REQUIRE(e.cross_section.size() == 5);
  CHECK(e.cross_section[2] == Eigen::Vector2d(0.34, 0.06));
  REQUIRE(e.spine.size() == 2);
  CHECK(e.spine[1] == Eigen::Vector3d(0, 0.05, 0));
  REQUIRE(e.orientation.size() == 1);
  CHECK(e.orientation[0].angle() == doctest::Approx(kPi / 2).epsilon(1e-15));
  CHECK(e.orientation[0].axis() == Eigen::Vector3d(0, 1, 0));
  REQUIRE(e.scale.size() == 1);
  CHECK(e.scale[0] == Eigen::Vector2d(1, 2));
  CHECK(e.crease_angle == doctest::Approx(kPi / 6).epsilon(1e-15));
  CHECK_FALSE(e.begin_cap);
  CHECK_FALSE(e.end_cap);
  CHECK(pos(r.take("load-legacy-key")) == Pos{15, 11});  // endCap
  CHECK(pos(r.take("load-legacy-key")) == Pos{19, 11});  // crossSection
  const auto& e2 = geometry_get<Extrusion>(s[1].geometry);
  CHECK(e2.cross_section.size() == 3);
  CHECK(e2.begin_cap);  // begin_cap is not read
  CHECK(pos(r.take("load-ignored-key")) == Pos{21, 22});
  r.expect_clean();
}

TEST_CASE("load: Extrusion with fewer than two spine points is geometry-degenerate") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Extrusion, cross_section: [0, 0, 1, 0], spine: [0, 0, 0]}
)");
  CHECK(pos(r.take("geometry-degenerate")) == Pos{7, 19});
  r.expect_clean();
}

TEST_CASE("load: ElevationGrid keys and height count") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry:
          type: ElevationGrid
          x_dimension: 2
          z_dimension: 3
          x_spacing: 0.5
          zSpacing: 0.25
          height: [0, 1, 2, 3, 4, 5]
          ccw: false
      - type: Shape
        geometry:
          type: ElevationGrid
          x_dimension: 2
          z_dimension: 3
          height: [0, 1, 2, 3, 4]
)");
  CHECK(pos(r.take("load-legacy-key")) == Pos{12, 11});  // zSpacing
  const auto& g = geometry_get<ElevationGrid>(r.link("A").shapes.at(0).geometry);
  CHECK(g.x_dimension == 2);
  CHECK(g.z_dimension == 3);
  CHECK(g.x_spacing == 0.5);
  CHECK(g.z_spacing == 0.25);
  CHECK(g.height == std::vector<double>{0, 1, 2, 3, 4, 5});
  CHECK_FALSE(g.ccw);
  // 2 * 3 = 6 heights are needed; 5 is an error at the geometry mapping.
  auto d = r.take("geometry-degenerate");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{17, 11});
  r.expect_clean();
}

TEST_CASE("load: IndexedFaceSet keys, out-of-range index and unterminated last polygon") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry:
          type: IndexedFaceSet
          vertices: [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
          faces: [0, 1, 2, 3, -1]
          tex_coords: [0, 0, 1, 0, 1, 1, 0, 1]
          tex_coord_indices: [0, 1, 2, 3, -1]
          crease_angle: 45
      - type: Shape
        geometry:
          type: IndexedFaceSet
          vertices: [0, 0, 0, 1, 0, 0, 1, 1, 0]
          faces: [0, 1, 3, -1]
      - type: Shape
        geometry:
          type: IndexedFaceSet
          coordinate: [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
          coordIndex: [0, 1, 2, -1, 0, 2, 3]
)");
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 3);
  const auto& f = geometry_get<IndexedFaceSet>(s[0].geometry);
  REQUIRE(f.vertices.size() == 4);
  CHECK(f.vertices[2] == Eigen::Vector3d(1, 1, 0));
  CHECK(f.faces == std::vector<int>{0, 1, 2, 3, -1});
  REQUIRE(f.tex_coords.size() == 4);
  CHECK(f.tex_coords[3] == Eigen::Vector2d(0, 1));
  CHECK(f.tex_coord_indices == std::vector<int>{0, 1, 2, 3, -1});
  CHECK(f.crease_angle == doctest::Approx(kPi / 4).epsilon(1e-15));
  // Index 3 with 3 vertices: error at the faces list.
  auto d = r.take("geometry-index-out-of-range");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{18, 18});
  // Last polygon without -1: warning at the faces list.
  auto w = r.take("geometry-unterminated-polygon");
  CHECK(w.severity == Severity::kWarning);
  CHECK(pos(w) == Pos{23, 23});
  CHECK(pos(r.take("load-legacy-key")) == Pos{22, 11});  // coordinate
  CHECK(pos(r.take("load-legacy-key")) == Pos{23, 11});  // coordIndex
  r.expect_clean();
}

TEST_CASE("load: TriangleMesh keys") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry:
          type: TriangleMesh
          vertices: [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
          faces: [0, 1, 2, 0, 2, 3]
      - type: Shape
        geometry:
          type: TriangleMesh
          vertices: [0, 0, 0, 1, 0, 0, 1, 1, 0]
          faces: [0, 1, 2, 0]
)");
  const auto& m = geometry_get<TriangleMeshGeometry>(r.link("A").shapes.at(0).geometry);
  CHECK(m.vertices.size() == 4);
  CHECK(m.faces == std::vector<int>{0, 1, 2, 0, 2, 3});
  CHECK(pos(r.take("geometry-degenerate")) == Pos{13, 11});
  r.expect_clean();
}

TEST_CASE("load: material defaults and explicit values") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Box}
        appearance: {material: {}}
      - type: Shape
        geometry: {type: Box}
        appearance:
          material:
            diffuse: [1, 0, 0]
            emissiveColor: [0, 0.5, 0]
            specular: [0.2, 0.2, 0.2]
            specular_exponent: 100
            ambient: 0.3
            transparency: 0.25
      - type: Shape
        geometry: {type: Box}
)");
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 3);
  REQUIRE(s[0].appearance.material.has_value());
  const Material& d = *s[0].appearance.material;
  CHECK(d.ambient_intensity == 1.0);
  CHECK(d.diffuse_color == Eigen::Vector3d(1, 1, 1));
  CHECK(d.emissive_color == Eigen::Vector3d(0, 0, 0));
  CHECK(d.specular_color == Eigen::Vector3d(0, 0, 0));
  CHECK(d.specular_exponent == 25.0);
  CHECK(d.transparency == 0.0);
  REQUIRE(s[1].appearance.material.has_value());
  const Material& m = *s[1].appearance.material;
  CHECK(m.diffuse_color == Eigen::Vector3d(1, 0, 0));
  CHECK(m.emissive_color == Eigen::Vector3d(0, 0.5, 0));
  CHECK(m.specular_color == Eigen::Vector3d(0.2, 0.2, 0.2));
  CHECK(m.specular_exponent == 100);
  CHECK(m.ambient_intensity == 0.3);
  CHECK(m.transparency == 0.25);  // 0 = opaque, 1 = invisible
  CHECK_FALSE(s[2].appearance.material.has_value());
  CHECK(pos(r.take("load-legacy-key")) == Pos{14, 13});  // emissiveColor
  r.expect_clean();
}

TEST_CASE("load: legacy shininess maps to specular_exponent = 127 * clamp(s, 0, 1) + 1") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - {type: Shape, geometry: {type: Box}, appearance: {material: {shininess: 0.5}}}
      - {type: Shape, geometry: {type: Box}, appearance: {material: {shininess: 2}}}
      - {type: Shape, geometry: {type: Box}, appearance: {material: {shininess: -1}}}
)");
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 3);
  CHECK(s[0].appearance.material->specular_exponent == 64.5);  // 127 * 0.5 + 1
  CHECK(s[1].appearance.material->specular_exponent == 128);   // clamped to 1
  CHECK(s[2].appearance.material->specular_exponent == 1);     // clamped to 0
  r.expect_clean();                                            // the shininess notes are informational
}

TEST_CASE("load: shininess next to specular_exponent is ignored with load-ignored-key") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Box}
        appearance:
          material: {specular_exponent: 10, shininess: 0.5}
)");
  CHECK(r.link("A").shapes.at(0).appearance.material->specular_exponent == 10);
  // "          material: {specular_exponent: 10, shininess: " is 55 characters.
  auto d = r.take("load-ignored-key");
  CHECK(d.severity == Severity::kWarning);
  CHECK(pos(d) == Pos{9, 56});
  r.expect_clean();
}

TEST_CASE("load: texture uri and repeat flags") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - {type: Shape, geometry: {type: Box}, appearance: {texture: {uri: tex.png, repeat: [true, false]}}}
      - {type: Shape, geometry: {type: Box}, appearance: {texture: {url: tex.png, repeat: false}}}
      - {type: Shape, geometry: {type: Box}, appearance: {texture: {uri: tex.png, repeat_t: false}}}
      - {type: Shape, geometry: {type: Box}, appearance: {texture: {uri: tex.png, repeat: [true]}}}
)");
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 4);
  const auto& t0 = *s[0].appearance.texture;
  CHECK(t0.uri == "tex.png");
  CHECK(t0.repeat_s);
  CHECK_FALSE(t0.repeat_t);
  const auto& t1 = *s[1].appearance.texture;
  CHECK_FALSE(t1.repeat_s);
  CHECK_FALSE(t1.repeat_t);
  const auto& t2 = *s[2].appearance.texture;
  CHECK(t2.repeat_s);
  CHECK_FALSE(t2.repeat_t);
  CHECK(s[3].appearance.texture->repeat_s);
  CHECK(s[3].appearance.texture->repeat_t);
  CHECK(pos(r.take("load-legacy-key")) == Pos{7, 69});  // url
  // "      - {type: Shape, geometry: {type: Box}, appearance: {texture: {uri: tex.png, repeat: "
  // is 90 characters. tex.png is not there: Choreonoid never reads repeat (see below).
  CHECK(pos(r.take("load-ignored-value")) == Pos{9, 91});
  r.expect_clean();
}

TEST_CASE("load: a Resource names its node by fragment before node, and specular_exponent falls back to shininess") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Resource, uri: missing.stl, fragment: F, node: N}
      - type: Shape
        geometry: {type: Box}
        appearance:
          material: {specular_exponent: high, shininess: 0.5}
)");
  // StdSceneReader::readResource: find({"fragment", "node"}). readMaterial: a specular_exponent
  // that does not read as a number falls to shininess, 127 * 0.5 + 1 = 64.5.
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 2);
  CHECK(bodyfmt::geometry_get<bodyfmt::MeshResource>(s[0].geometry).node == "F");
  CHECK(pos(r.take("load-ignored-key")) == Pos{7, 73});
  REQUIRE(s[1].appearance.material.has_value());
  CHECK(s[1].appearance.material->specular_exponent == 64.5);
  CHECK(pos(r.take("load-ignored-value")) == Pos{11, 41});
  r.take("mesh-file-missing");
  r.take("load-legacy-shininess");
  r.expect_clean();
}

TEST_CASE("load: texture repeat and texture_transform are checked where Choreonoid reads them, once the image loads") {
  // A file beside tests/data/gltf/checker.png, so that the texture resolves to an image.
  auto r = bodyfmt::test::load(R"(
format: ChoreonoidBody
format_version: 2.0
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Box}
        appearance:
          texture: {uri: checker.png, repeat: 1}
      - type: Shape
        geometry: {type: Box}
        appearance:
          texture: {uri: checker.png, repeat: [true, no please]}
          texture_transform: {center: [0.5], scale: 2, translation: [0, 0, 0], rotation: 90}
      - type: Shape
        geometry: {type: Box}
        appearance:
          texture: {uri: missing.png, repeat: 1}
          texture_transform: {center: [0.5]}
)",
                               std::string(BODYFMT_TEST_DATA_DIR) + "/gltf/texture_checks.body");
  // StdSceneReader::readTexture: repeat goes through toBool (which throws) once the image has
  // loaded; readTextureTransform reads Vector2s (a list of another size throws, a scalar is
  // skipped). Without the image neither is read.
  CHECK(pos(r.take("load-bool")) == Pos{9, 47});
  CHECK(pos(r.take("load-bool")) == Pos{13, 54});
  CHECK(pos(r.take("load-vector-size")) == Pos{14, 39});    // center
  CHECK(pos(r.take("load-ignored-value")) == Pos{14, 53});  // scale: 2
  CHECK(pos(r.take("load-vector-size")) == Pos{14, 69});    // translation
  CHECK(pos(r.take("load-ignored-value")) == Pos{18, 47});  // missing.png: repeat is never read
  const auto& s = r.link("A").shapes;
  REQUIRE(s.size() == 3);
  CHECK(s[1].appearance.texture->repeat_s);
  r.expect_clean();
}
