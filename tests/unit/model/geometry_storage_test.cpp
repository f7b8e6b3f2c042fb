// Geometry keeps its large alternatives (vectors, strings) on the heap, so that a shape of a
// primitive is small; they read, copy and compare as the plain structs.

#include <bodyfmt/model.h>

#include <doctest/doctest.h>

#include <variant>

using namespace bodyfmt;

TEST_CASE("Geometry is sized by the primitives") {
  CHECK(sizeof(Geometry) <= 32);  // a Box (24 bytes) and the index
  CHECK(sizeof(Geometry) < sizeof(MeshResource));
}

TEST_CASE("geometry_if, geometry_get and geometry_is read any alternative") {
  IndexedFaceSet faces;
  faces.vertices = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  faces.faces = {0, 1, 2, -1};
  Geometry g = faces;
  CHECK(geometry_is<IndexedFaceSet>(g));
  CHECK_FALSE(geometry_is<TriangleMeshGeometry>(g));
  CHECK(geometry_if<MeshResource>(g) == nullptr);
  CHECK(geometry_if<Box>(g) == nullptr);
  REQUIRE(geometry_if<IndexedFaceSet>(g) != nullptr);
  CHECK(geometry_get<IndexedFaceSet>(g).faces == std::vector<int>{0, 1, 2, -1});
  CHECK_THROWS_AS((void)geometry_get<Extrusion>(g), std::bad_variant_access);
  CHECK(geometry_type_name(g) == "IndexedFaceSet");

  g = Box{Eigen::Vector3d(1, 2, 3)};
  REQUIRE(geometry_if<Box>(g) != nullptr);
  CHECK(geometry_if<Box>(g)->size == Eigen::Vector3d(1, 2, 3));
  CHECK(std::get<Box>(g).size.z() == 3);
}

TEST_CASE("a copied shape owns its geometry") {
  Shape a;
  MeshResource mesh;
  mesh.uri = "meshes/arm.stl";
  mesh.mesh = 3;
  a.geometry = mesh;
  Shape b = a;
  geometry_if<MeshResource>(b.geometry)->uri = "meshes/leg.stl";
  CHECK(geometry_get<MeshResource>(a.geometry).uri == "meshes/arm.stl");
  CHECK(geometry_get<MeshResource>(b.geometry).uri == "meshes/leg.stl");
  CHECK(geometry_get<MeshResource>(b.geometry).mesh == 3);
  a = b;
  CHECK(geometry_get<MeshResource>(a.geometry).uri == "meshes/leg.stl");
  Shape moved = std::move(b);
  CHECK(geometry_get<MeshResource>(moved.geometry).uri == "meshes/leg.stl");
}
