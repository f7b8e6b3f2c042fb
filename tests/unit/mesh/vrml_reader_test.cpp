// The VRML97 reader on small inputs: structure, transforms, lenient forms and malformed text.
#include <bodyfmt/mesh_import.h>
#include <doctest/doctest.h>

#include "mesh_import/scene_tree.h"
#include "mesh_import/vrml_reader.h"
#include "mesh_test_support.h"

#include <bodyfmt/tessellate.h>

#include <fstream>
#include <sstream>

using namespace bodyfmt;
using namespace mesh_test;

namespace {

std::vector<MeshPart> parts_of(const std::string& text, const std::string& node = "",
                               CollectingSink* sink_out = nullptr) {
  CollectingSink local;
  CollectingSink& sink = sink_out ? *sink_out : local;
  auto tree = mesh::read_vrml(text, "test.wrl", sink, {});
  std::vector<MeshPart> parts;
  if (tree) mesh::extract_parts(*tree, node, 1.0, false, parts);
  return parts;
}

BoundingBox box_of_parts(const std::vector<MeshPart>& parts) {
  MeshAsset asset;
  asset.parts = parts;
  return box_of(asset);
}

double volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) {
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6;
  }
  return v;
}

}  // namespace

TEST_CASE("vrml: IndexedFaceSet, Material and the missing #VRML header") {
  const char* text = R"(
    Shape {
      appearance Appearance { material Material { diffuseColor 0.1 0.2 0.3 shininess 0.5 transparency 0.25 } }
      geometry IndexedFaceSet {
        coord Coordinate { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0 ] }
        coordIndex [ 0 1 2 3 -1 ]
      }
    })";
  CollectingSink sink;
  auto parts = parts_of(text, "", &sink);
  CHECK(sink.diagnostics().empty());
  REQUIRE(parts.size() == 1);
  CHECK(parts[0].mesh.triangles.size() == 2);
  REQUIRE(parts[0].material);
  CHECK(parts[0].material->diffuse_color.isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  CHECK(parts[0].material->ambient_intensity == doctest::Approx(0.2));  // VRML default
  CHECK(parts[0].material->specular_exponent == doctest::Approx(127 * 0.5 + 1));
  CHECK(parts[0].material->transparency == doctest::Approx(0.25));
  // ccw FALSE flips the winding; the last polygon may go without -1.
  auto flipped = parts_of(R"(Shape { geometry IndexedFaceSet { ccw FALSE
      coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] } coordIndex [ 0 1 2 ] } })");
  REQUIRE(flipped.size() == 1);
  CHECK(flipped[0].mesh.triangles[0] == std::array<int, 3>{0, 2, 1});
}

TEST_CASE("vrml: Transform composes T C R SR S -SR -C and DEF/USE instances subtrees") {
  const char* text = R"(#VRML V2.0 utf8
    DEF T Transform {
      translation 1 2 3
      rotation 0 0 1 1.5707963267948966
      scale 2 1 1
      children [ DEF B Shape { geometry Box { size 1 1 1 } } ]
    }
    Transform { translation 10 0 0 children USE B })";
  auto parts = parts_of(text);
  REQUIRE(parts.size() == 2);
  // Box scaled 2 along x, then turned 90 deg about z: 1 wide in x, 2 in y; then translated.
  const BoundingBox a = box_of_parts({parts[0]});
  CHECK(a.min.isApprox(Eigen::Vector3d(0.5, 1, 2.5)));
  CHECK(a.max.isApprox(Eigen::Vector3d(1.5, 3, 3.5)));
  const BoundingBox b = box_of_parts({parts[1]});
  CHECK(b.min.isApprox(Eigen::Vector3d(9.5, -0.5, -0.5)));
  CHECK(volume(parts[0].mesh) == doctest::Approx(2.0));
}

TEST_CASE("vrml: a selected node is re-centred: translations dropped, rotation and scale kept") {
  const char* text = R"(
    Transform { translation 5 5 5 rotation 1 0 0 1.5707963267948966 scale 2 2 2 children [
      DEF PART Transform { translation 1 0 0 children [
        Transform { translation 0 0 1 children Shape { geometry Box { size 1 2 3 } } } ] } ] })";
  auto parts = parts_of(text, "PART");
  REQUIRE(parts.size() == 1);
  const BoundingBox box = box_of_parts(parts);
  // Child translation (0 0 1) is kept and goes through the kept rotation and scale: the box
  // (1 2 3) scaled x2 is (2 4 6), turned about x: y<-(-z), z<-y; centre (0 0 1)*2 -> (0 -2 0).
  CHECK(box.min.isApprox(Eigen::Vector3d(-1, -5, -2)));
  CHECK(box.max.isApprox(Eigen::Vector3d(1, 1, 2)));
}

TEST_CASE("vrml: lenient `DEF Transform {` reads an unnamed Transform") {
  auto parts =
      parts_of(R"(DEF Transform { translation 0 0 1 children [ DEF S Shape { geometry Sphere { radius 0.5 } } ] })");
  REQUIRE(parts.size() == 1);
  const BoundingBox box = box_of_parts(parts);
  CHECK(box.max.z() == doctest::Approx(1.5));
  CHECK(box.min.z() == doctest::Approx(0.5));
}

TEST_CASE("vrml: unknown nodes, PROTO, ROUTE and unknown fields are skipped") {
  const char* text = R"(#VRML V2.0 utf8
    PROTO Joint [ field SFVec3f t 0 0 0 exposedField MFNode children [] ] { Transform { translation IS t children IS children } }
    EXTERNPROTO Ext [ field SFFloat x ] [ "urn:x" "ext.wrl#Ext" ]
    Viewpoint { position 0 0 10 orientation 0 1 0 0 description "front { ] view" }
    NavigationInfo { type [ "EXAMINE", "ANY" ] headlight TRUE }
    Joint { t 1 2 3 children [ Shape { geometry Box {} } ] }
    DEF G Group { bboxCenter 0 0 0 bboxSize -1 -1 -1 children [
      Shape { appearance Appearance { textureTransform TextureTransform { scale 2 2 } }
              geometry Cylinder { radius 0.5 height 2 side TRUE } }
      DirectionalLight { direction 0 0 -1 }
    ] }
    ROUTE A.x TO B.y)";
  CollectingSink sink;
  auto parts = parts_of(text, "", &sink);
  CHECK(sink.diagnostics().empty());
  REQUIRE(parts.size() == 1);
  const BoundingBox box = box_of_parts(parts);
  CHECK(box.min.isApprox(Eigen::Vector3d(-0.5, -1, -0.5)));
  CHECK(box.max.isApprox(Eigen::Vector3d(0.5, 1, 0.5)));
  CHECK(volume(parts[0].mesh) > 0);
}

TEST_CASE("vrml: primitives are closed and outward-facing") {
  auto parts = parts_of(R"(Shape { geometry Box { size 1 2 3 } } Shape { geometry Sphere { radius 1 } }
                           Shape { geometry Cylinder { radius 1 height 2 } } Shape { geometry Cone { bottomRadius 1 height 2 } })");
  REQUIRE(parts.size() == 4);
  CHECK(volume(parts[0].mesh) == doctest::Approx(6));
  CHECK(volume(parts[1].mesh) == doctest::Approx(4.18879).epsilon(0.05));
  CHECK(volume(parts[2].mesh) == doctest::Approx(6.28319).epsilon(0.05));
  CHECK(volume(parts[3].mesh) == doctest::Approx(2.0944).epsilon(0.05));
}

TEST_CASE("vrml: malformed input gives a located mesh-parse error and no scene") {
  struct Case {
    const char* text;
    int line;
    int column;
  };
  const Case cases[] = {
      {"Shape {\n  geometry Box { size 1 x 1 }\n}", 2, 25},          // not a number
      {"Transform {\n  children [ Shape { }\n", 3, 1},               // end of file
      {"Transform { translation 0 0 0 } }", 1, 33},                  // stray brace
      {"Shape { geometry USE NOPE }", 1, 22},                        // undefined USE
      {"Group { children [ Shape { appearance \"x\" } ] }", 1, 39},  // string as a node
      {"Viewpoint { description \"unterminated }", 1, 25},           // unterminated string
      {"Group { children [ Foo { a [ 1 2 } ] }", 1, 34},             // unbalanced skip
      // An index beyond int (fuzz_load: UBSan on the conversion) and one that is not whole.
      {"Shape { geometry IndexedFaceSet { coordIndex [ 0 1 313e13 -1 ] } }", 1, 52},
      {"Shape { geometry IndexedFaceSet { coordIndex [ 0 1.5 2 -1 ] } }", 1, 50},
  };
  for (const Case& c : cases) {
    CAPTURE(std::string(c.text));
    CollectingSink sink;
    auto tree = mesh::read_vrml(c.text, "bad.wrl", sink, {});
    CHECK_FALSE(tree);
    REQUIRE(sink.diagnostics().size() == 1);
    const Diagnostic& d = sink.diagnostics().front();
    CHECK(d.rule_id == "mesh-parse");
    CHECK(d.location.file == "bad.wrl");
    CHECK(d.location.line == c.line);
    CHECK(d.location.column == c.column);
  }
}

TEST_CASE("vrml: deep nesting and truncated corpus text never crash or hang") {
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "Group { children [ ";
  CollectingSink sink;
  CHECK_FALSE(mesh::read_vrml(deep, "deep.wrl", sink, {}));
  CHECK(sink.has("mesh-parse"));

  std::ifstream in(kCorpus + "PA10/parts/J3.wrl");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  REQUIRE(text.size() > 1000);
  for (std::size_t cut = 0; cut < text.size(); cut += 97) {
    CollectingSink s;
    auto tree = mesh::read_vrml(std::string_view(text).substr(0, cut), "cut.wrl", s, {});
    CHECK((tree != nullptr || s.has("mesh-parse")));
  }
}

TEST_CASE("vrml: Inline is resolved relative to the including file, cycles are reported") {
  const std::string dir = std::string(BODYFMT_TEST_DATA_DIR) + "/mesh/";
  MeshCache cache;
  CollectingSink sink;
  auto asset = cache.get(dir + "inline_parent.wrl", {}, sink, {});
  REQUIRE(asset);
  CHECK(sink.diagnostics().empty());
  CHECK(cache.files_parsed() == 2);
  const BoundingBox box = box_of(*asset);
  CHECK(box.min.isApprox(Eigen::Vector3d(0.9, -0.2, -0.3)));
  CHECK(box.max.isApprox(Eigen::Vector3d(1.1, 0.2, 0.3)));
  // A node inside the inlined file is found by name too.
  MeshImportOptions options;
  options.node = "CHILD_BOX";
  auto child = cache.get(dir + "inline_parent.wrl", options, sink, {});
  REQUIRE(child);
  CHECK(box_of(*child).max.isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));  // scale 2 kept

  CollectingSink cycle;
  auto looped = import_mesh(dir + "inline_cycle.wrl", {}, cycle, {});
  REQUIRE(looped);  // the sphere is still there
  CHECK(cycle.has("mesh-inline-cycle"));
}

TEST_CASE("vrml: primitives use the shared tessellator with VRML97 defaults") {
  auto parts = parts_of(R"(Shape { geometry Box { } } Shape { geometry Sphere { } }
                           Shape { geometry Cylinder { } } Shape { geometry Cone { } })");
  REQUIRE(parts.size() == 4);
  CollectingSink sink;
  // VRML97 defaults: Box 2 2 2, Sphere radius 1, Cylinder radius 1 height 2, Cone
  // bottomRadius 1 height 2; the same meshes as bodyfmt::tessellate() of those geometries.
  const Geometry expected[] = {Box{Eigen::Vector3d(2, 2, 2)}, Sphere{1}, Cylinder{1, 2, true, true}, Cone{1, 2, true}};
  for (int i = 0; i < 4; ++i) {
    CAPTURE(i);
    const TriangleMesh mesh = tessellate(expected[i], kDefaultDivisionNumber, sink, {});
    CHECK(parts[i].mesh.vertices == mesh.vertices);
    CHECK(parts[i].mesh.triangles == mesh.triangles);
  }
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("vrml: primitive flags and invalid sizes") {
  // side FALSE drops the side but keeps every vertex (the box is unchanged); top/bottom FALSE
  // drop the caps.
  auto parts = parts_of(R"(Shape { geometry Cylinder { side FALSE } }
                           Shape { geometry Cylinder { top FALSE bottom FALSE } }
                           Shape { geometry Cone { side FALSE } })");
  REQUIRE(parts.size() == 3);
  const int n = kDefaultDivisionNumber;
  CHECK(parts[0].mesh.triangles.size() == static_cast<std::size_t>(2 * n));
  CHECK(box_of_parts({parts[0]}).max.isApprox(Eigen::Vector3d(1, 1, 1)));
  CHECK(parts[1].mesh.triangles.size() == static_cast<std::size_t>(2 * n));
  CHECK(parts[2].mesh.triangles.size() == static_cast<std::size_t>(n));
  CHECK(box_of_parts({parts[2]}).max.y() == doctest::Approx(1));  // apex kept

  // A negative size is the tessellator's error, located at the primitive in the mesh file.
  CollectingSink sink;
  auto bad = parts_of("Shape {\n  geometry Sphere { radius -1 } }", "", &sink);
  CHECK(bad.empty());
  REQUIRE(sink.diagnostics().size() == 1);
  CHECK(sink.diagnostics()[0].rule_id == "geometry-invalid-size");
  CHECK(sink.diagnostics()[0].location.file == "test.wrl");
  CHECK(sink.diagnostics()[0].location.line == 2);
}

TEST_CASE("scene tree: a zero scale flattens a mesh with normals to finite normals") {
  // The scene tree (VRML Transforms, assimp's nodes) transforms meshes as append_mesh does
  // (bodyfmt::transform_mesh): its own copy took the inverse of a singular scale, and every
  // normal came out NaN.
  MeshPart part;
  part.mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  part.mesh.normals = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.6, 0.8, 0}};
  part.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh::SceneNode node;
  node.transform = Eigen::Affine3d(Eigen::Scaling(0.0, 1.0, 1.0));
  node.parts.push_back(part);
  std::vector<MeshPart> parts;
  mesh::flatten(node, Eigen::Affine3d::Identity(), parts);
  REQUIRE(parts.size() == 1);
  const TriangleMesh& m = parts[0].mesh;
  REQUIRE(m.normals.size() == m.vertices.size());
  for (const Eigen::Vector3d& n : m.normals) {
    CAPTURE(n.transpose());
    CHECK(n.allFinite());
    // The squashed axis is x: the surface left lies in the plane x = 0, whose normal is ±x (none
    // where the squash left no direction).
    CHECK((n.isZero() || std::abs(std::abs(n.x()) - 1) < 1e-12));
  }
  for (const Eigen::Vector3d& v : m.vertices) CHECK(v.x() == 0);
}
