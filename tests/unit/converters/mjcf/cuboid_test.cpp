// exact_cuboid (body2mjcf): which triangle meshes are exactly a rectangular box, and the box's
// pose and edges; each near miss is refused.
#include "cuboid.h"

#include <doctest/doctest.h>

#include <array>
#include <cmath>

using bodyfmt::TriangleMesh;
using bodyfmt::mjcf::exact_cuboid;

namespace {

// Corners (±1, ±1, ±1) in bit order (x: bit 0, y: bit 1, z: bit 2), faces as quads.
const std::array<std::array<int, 4>, 6> kQuads = {
    {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {1, 3, 7, 5}, {0, 4, 6, 2}}};

TriangleMesh box(const Eigen::Vector3d& half, const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity()) {
  TriangleMesh mesh;
  for (int c = 0; c < 8; ++c)
    mesh.vertices.push_back(
        pose * Eigen::Vector3d((c & 1 ? 1 : -1) * half.x(), (c & 2 ? 1 : -1) * half.y(), (c & 4 ? 1 : -1) * half.z()));
  for (const auto& q : kQuads) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

}  // namespace

TEST_CASE("cuboid: an axis-aligned box off the origin, with its centre and half edges") {
  Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
  at.translation() = Eigen::Vector3d(0.01, 0.02, 0.03);
  const auto found = exact_cuboid(box({0.085, 0.01, 0.06}, at));
  REQUIRE(found);
  CHECK(found->pose.linear().isIdentity(1e-15));
  CHECK((found->pose.translation() - at.translation()).norm() < 1e-15);
  CHECK((found->half_edges - Eigen::Vector3d(0.085, 0.01, 0.06)).norm() < 1e-15);
}

TEST_CASE("cuboid: a turned box is found with its rotation, a scale applies per axis") {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(-0.2, 0.1, 0.3);
  const TriangleMesh mesh = box({0.3, 0.2, 0.1}, pose);
  const auto found = exact_cuboid(mesh);
  REQUIRE(found);
  CHECK(found->pose.linear().determinant() == doctest::Approx(1.0));
  // Each corner of the box found is a vertex of the mesh.
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d h = found->half_edges;
    const Eigen::Vector3d corner =
        found->pose * Eigen::Vector3d((c & 1 ? 1 : -1) * h.x(), (c & 2 ? 1 : -1) * h.y(), (c & 4 ? 1 : -1) * h.z());
    double nearest = 1;
    for (const Eigen::Vector3d& v : mesh.vertices) nearest = std::min(nearest, (v - corner).norm());
    CHECK(nearest < 1e-12);
  }
  // The axes are the mesh axes the edges are closest to: a small turn keeps the edges' order.
  Eigen::Isometry3d small = Eigen::Isometry3d::Identity();
  small.linear() = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const auto near_aligned = exact_cuboid(box({0.3, 0.2, 0.1}, small));
  REQUIRE(near_aligned);
  CHECK((near_aligned->half_edges - Eigen::Vector3d(0.3, 0.2, 0.1)).norm() < 1e-12);
  CHECK((near_aligned->pose.linear() - small.linear()).norm() < 1e-12);
  const auto stretched = exact_cuboid(box({1, 1, 1}), Eigen::Vector3d(0.5, 2, 3));
  REQUIRE(stretched);
  CHECK((stretched->half_edges - Eigen::Vector3d(0.5, 2, 3)).norm() < 1e-12);
}

TEST_CASE("cuboid: corners written more than once (a vertex per face) and unused vertices do not matter") {
  TriangleMesh split;
  const TriangleMesh b = box({0.1, 0.2, 0.3});
  for (const auto& t : b.triangles) {
    const int base = static_cast<int>(split.vertices.size());
    for (int i : t) split.vertices.push_back(b.vertices[i]);
    split.triangles.push_back({base, base + 1, base + 2});
  }
  split.vertices.push_back(Eigen::Vector3d(5, 5, 5));  // referenced by no triangle
  CHECK(exact_cuboid(split));
  // A corner 5e-8 m off, within 1e-6 of the 0.75 m diagonal, still makes the box.
  TriangleMesh close = b;
  close.vertices[6] += Eigen::Vector3d(5e-8, 0, 0);
  CHECK(exact_cuboid(close));
}

TEST_CASE("cuboid: near misses stay meshes") {
  const TriangleMesh b = box({0.085, 0.01, 0.06});
  SUBCASE("a corner 1e-5 of the diagonal off") {
    TriangleMesh m = b;
    m.vertices[7] += Eigen::Vector3d(0, 0, 2.1e-6);
    CHECK_FALSE(exact_cuboid(m));
  }
  SUBCASE("a parallelepiped") {
    TriangleMesh m = b;
    for (auto& v : m.vertices)
      if (v.z() > 0) v.x() += 0.03;
    CHECK_FALSE(exact_cuboid(m));
  }
  SUBCASE("a face missing") {
    TriangleMesh m = b;
    m.triangles.resize(10);
    CHECK_FALSE(exact_cuboid(m));
  }
  SUBCASE("a triangle through the inside") {
    TriangleMesh m = b;
    m.triangles.push_back({0, 3, 7});
    CHECK_FALSE(exact_cuboid(m));
  }
  SUBCASE("two triangles per face that overlap and leave a quarter open") {
    TriangleMesh m = b;
    m.triangles.clear();
    for (const auto& q : kQuads) {
      m.triangles.push_back({q[0], q[1], q[2]});
      m.triangles.push_back({q[0], q[1], q[3]});
    }
    CHECK_FALSE(exact_cuboid(m));
  }
  SUBCASE("a ninth corner") {
    TriangleMesh m = b;
    m.vertices.push_back(Eigen::Vector3d(0, 0, 0.06));
    m.triangles[2] = {4, 5, 8};
    CHECK_FALSE(exact_cuboid(m));
  }
  SUBCASE("a flat box and an empty mesh") {
    CHECK_FALSE(exact_cuboid(box({0.1, 0.1, 0})));
    CHECK_FALSE(exact_cuboid(TriangleMesh{}));
  }
  SUBCASE("an index out of range") {
    TriangleMesh m = b;
    m.triangles[0][1] = 99;
    CHECK_FALSE(exact_cuboid(m));
  }
}
