// Unit tests for mesh.h: bounding boxes, signed volume, append_mesh.
#include <bodyfmt/angles.h>
#include <bodyfmt/mesh.h>
#include <doctest/doctest.h>

#include <cmath>

using bodyfmt::BoundingBox;
using bodyfmt::TriangleMesh;
using Eigen::Vector3d;

namespace {

using bodyfmt::kPi;

// Axis-aligned box [0, sx] x [0, sy] x [0, sz], triangles counter-clockwise from outside.
TriangleMesh corner_box(double sx, double sy, double sz) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k) {
    m.vertices.emplace_back((k & 1) ? sx : 0, (k & 2) ? sy : 0, (k & 4) ? sz : 0);
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

}  // namespace

TEST_CASE("mesh: bounding box of an empty mesh is empty") {
  TriangleMesh m;
  CHECK(bodyfmt::bounding_box(m).empty());
  CHECK(bodyfmt::bounding_box(m, Eigen::Affine3d(Eigen::Translation3d(1, 2, 3))).empty());
}

TEST_CASE("mesh: bounding box with and without a transform") {
  const TriangleMesh m = corner_box(1, 2, 3);
  const BoundingBox local = bodyfmt::bounding_box(m);
  CHECK(local.min.isApprox(Vector3d(0, 0, 0)));
  CHECK(local.max.isApprox(Vector3d(1, 2, 3)));

  // 90 degrees about Z maps (x, y, z) -> (-y, x, z); then translate by (10, 0, 0).
  Eigen::Affine3d t = Eigen::Translation3d(10, 0, 0) * Eigen::AngleAxisd(kPi / 2, Vector3d::UnitZ());
  const BoundingBox moved = bodyfmt::bounding_box(m, t);
  CHECK((moved.min - Vector3d(8, 0, 0)).norm() < 1e-12);
  CHECK((moved.max - Vector3d(10, 1, 3)).norm() < 1e-12);
}

TEST_CASE("mesh: signed volume of a box is exact, sign follows the winding") {
  TriangleMesh m = corner_box(1, 2, 3);
  CHECK(bodyfmt::signed_volume(m) == doctest::Approx(6.0).epsilon(1e-14));
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  CHECK(bodyfmt::signed_volume(m) == doctest::Approx(-6.0).epsilon(1e-14));
}

TEST_CASE("mesh: signed volume of a closed mesh does not depend on its position") {
  TriangleMesh moved;
  bodyfmt::append_mesh(moved, corner_box(1, 1, 1), Eigen::Affine3d(Eigen::Translation3d(-5, 7, 100)));
  CHECK(bodyfmt::signed_volume(moved) == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("mesh: signed volume skips triangles with bad indices") {
  TriangleMesh m = corner_box(1, 1, 1);
  m.triangles.push_back({0, 1, 99});
  m.triangles.push_back({-1, 1, 2});
  CHECK(bodyfmt::signed_volume(m) == doctest::Approx(1.0));
}

TEST_CASE("mesh: append_mesh offsets indices and transforms vertices") {
  TriangleMesh m = corner_box(1, 1, 1);
  const TriangleMesh other = corner_box(1, 1, 1);
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  t.translate(Vector3d(2, 0, 0));
  t.scale(Vector3d(2, 1, 1));
  bodyfmt::append_mesh(m, other, t);
  REQUIRE(m.vertices.size() == 16);
  REQUIRE(m.triangles.size() == 24);
  CHECK(m.triangles[12][0] == other.triangles[0][0] + 8);
  CHECK(m.vertices[9].isApprox(Vector3d(4, 0, 0)));  // (1,0,0) scaled by 2, moved by 2
  // 1 + 2 (the stretched copy).
  CHECK(bodyfmt::signed_volume(m) == doctest::Approx(3.0));
  const BoundingBox box = bodyfmt::bounding_box(m);
  CHECK(box.max.isApprox(Vector3d(4, 1, 1)));
}

TEST_CASE("mesh: append_mesh keeps triangles outward under a mirror") {
  TriangleMesh m;
  Eigen::Affine3d mirror = Eigen::Affine3d::Identity();
  mirror.scale(Vector3d(-1, 1, 1));
  bodyfmt::append_mesh(m, corner_box(1, 2, 3), mirror);
  CHECK(bodyfmt::signed_volume(m) == doctest::Approx(6.0));
}

TEST_CASE("mesh: append_mesh maps normals with the inverse transpose and renormalises") {
  TriangleMesh other;
  other.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  other.triangles = {{0, 1, 2}};
  // A normal of the plane x + y = const.
  const Vector3d n = Vector3d(1, 1, 0).normalized();
  other.normals = {n, n, Vector3d::UnitZ()};

  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  t.scale(Vector3d(2, 1, 1));  // the plane x + y = c becomes x / 2 + y = c
  TriangleMesh m;
  bodyfmt::append_mesh(m, other, t);
  REQUIRE(m.normals.size() == 3);
  CHECK((m.normals[0] - Vector3d(0.5, 1, 0).normalized()).norm() < 1e-12);
  CHECK(m.normals[0].norm() == doctest::Approx(1.0));
  CHECK((m.normals[2] - Vector3d::UnitZ()).norm() < 1e-12);

  // Mirror: an outward normal stays outward (points to -X after x -> -x).
  TriangleMesh mirrored;
  Eigen::Affine3d mirror = Eigen::Affine3d::Identity();
  mirror.scale(Vector3d(-1, 1, 1));
  TriangleMesh single = other;
  single.normals = {Vector3d::UnitX(), Vector3d::UnitX(), Vector3d::UnitX()};
  bodyfmt::append_mesh(mirrored, single, mirror);
  CHECK((mirrored.normals[0] - Vector3d(-1, 0, 0)).norm() < 1e-12);

  // A singular transform (zero scale) must not produce NaN.
  TriangleMesh flat;
  Eigen::Affine3d squash = Eigen::Affine3d::Identity();
  squash.scale(Vector3d(1, 1, 0));
  bodyfmt::append_mesh(flat, other, squash);
  for (const Vector3d& v : flat.normals) CHECK(v.allFinite());
  CHECK((flat.normals[2] - Vector3d::UnitZ()).norm() < 1e-12);
}

TEST_CASE("mesh: append_mesh drops per-vertex attributes one side lacks") {
  TriangleMesh with;
  with.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  with.triangles = {{0, 1, 2}};
  with.normals.assign(3, Vector3d::UnitZ());
  with.tex_coords.assign(3, Eigen::Vector2d(0.5, 0.5));
  TriangleMesh without = with;
  without.normals.clear();
  without.tex_coords.clear();

  TriangleMesh a;
  bodyfmt::append_mesh(a, with);  // an empty target adopts the attributes
  CHECK(a.normals.size() == 3);
  CHECK(a.tex_coords.size() == 3);
  bodyfmt::append_mesh(a, with);
  CHECK(a.normals.size() == 6);
  CHECK(a.tex_coords.size() == 6);
  bodyfmt::append_mesh(a, without);
  CHECK(a.vertices.size() == 9);
  CHECK(a.normals.empty());
  CHECK(a.tex_coords.empty());
}
