#include "mesh/primitives.h"

#include <cmath>

namespace bodyfmt::mesh {

namespace {
constexpr double kPi = 3.14159265358979323846;

void add_quad(TriangleMesh& m, int a, int b, int c, int d) {  // counter-clockwise a b c d
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}
}  // namespace

TriangleMesh make_box(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const Eigen::Vector3d h = size / 2;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  }
  add_quad(m, 0, 4, 6, 2);  // -X
  add_quad(m, 1, 3, 7, 5);  // +X
  add_quad(m, 0, 1, 5, 4);  // -Y
  add_quad(m, 2, 6, 7, 3);  // +Y
  add_quad(m, 0, 2, 3, 1);  // -Z
  add_quad(m, 4, 5, 7, 6);  // +Z
  return m;
}

TriangleMesh make_sphere(double radius, int division) {
  TriangleMesh m;
  const int rings = division / 2;  // latitude bands
  m.vertices.emplace_back(0, radius, 0);  // north pole
  for (int j = 1; j < rings; ++j) {
    const double phi = kPi * j / rings;
    for (int i = 0; i < division; ++i) {
      const double theta = 2 * kPi * i / division;
      m.vertices.emplace_back(radius * std::sin(phi) * std::cos(theta), radius * std::cos(phi),
                              -radius * std::sin(phi) * std::sin(theta));
    }
  }
  const int south = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0, -radius, 0);
  const auto ring = [&](int j, int i) { return 1 + (j - 1) * division + (i % division); };
  for (int i = 0; i < division; ++i) m.triangles.push_back({0, ring(1, i), ring(1, i + 1)});
  for (int j = 1; j + 1 < rings; ++j) {
    for (int i = 0; i < division; ++i) add_quad(m, ring(j, i), ring(j + 1, i), ring(j + 1, i + 1), ring(j, i + 1));
  }
  for (int i = 0; i < division; ++i) {
    m.triangles.push_back({south, ring(rings - 1, i + 1), ring(rings - 1, i)});
  }
  return m;
}

TriangleMesh make_cylinder(double radius, double height, bool bottom, bool side, bool top,
                           int division) {
  TriangleMesh m;
  const double y = height / 2;
  for (int i = 0; i < division; ++i) {  // top ring then bottom ring
    const double a = 2 * kPi * i / division;
    m.vertices.emplace_back(radius * std::cos(a), y, -radius * std::sin(a));
  }
  for (int i = 0; i < division; ++i) {
    const double a = 2 * kPi * i / division;
    m.vertices.emplace_back(radius * std::cos(a), -y, -radius * std::sin(a));
  }
  const int top_centre = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0, y, 0);
  m.vertices.emplace_back(0, -y, 0);
  const int bottom_centre = top_centre + 1;
  for (int i = 0; i < division; ++i) {
    const int j = (i + 1) % division;
    if (side) add_quad(m, i, division + i, division + j, j);
    if (top) m.triangles.push_back({top_centre, i, j});
    if (bottom) m.triangles.push_back({bottom_centre, division + j, division + i});
  }
  return m;
}

TriangleMesh make_cone(double radius, double height, bool bottom, bool side, int division) {
  TriangleMesh m;
  const double y = height / 2;
  for (int i = 0; i < division; ++i) {
    const double a = 2 * kPi * i / division;
    m.vertices.emplace_back(radius * std::cos(a), -y, -radius * std::sin(a));
  }
  const int apex = division;
  m.vertices.emplace_back(0, y, 0);
  m.vertices.emplace_back(0, -y, 0);
  const int bottom_centre = division + 1;
  for (int i = 0; i < division; ++i) {
    const int j = (i + 1) % division;
    if (side) m.triangles.push_back({apex, i, j});
    if (bottom) m.triangles.push_back({bottom_centre, j, i});
  }
  return m;
}

}  // namespace bodyfmt::mesh
