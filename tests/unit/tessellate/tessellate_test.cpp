// Unit tests for tessellate.h. Expected values are analytic: exact volumes of the polyhedra the
// tessellator must produce (derived in comments), plus a loose comparison with the smooth solid.
#include <bodyfmt/angles.h>
#include <bodyfmt/tessellate.h>
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

using namespace bodyfmt;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

using bodyfmt::kPi;
const SourceLocation kWhere{"robot.body", 12, 7};

TriangleMesh run(const Geometry& geometry, int division, CollectingSink& sink) {
  return tessellate(geometry, division, sink, kWhere);
}

/// Closed and consistently oriented: every directed edge occurs exactly once and so does its
/// reverse, i.e. every edge is shared by exactly two triangles that traverse it oppositely.
bool closed_and_consistent(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> count;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++count[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, n] : count) {
    if (n != 1) return false;
    const auto reverse = count.find({edge.second, edge.first});
    if (reverse == count.end() || reverse->second != 1) return false;
  }
  return !mesh.triangles.empty();
}

void check_box(const TriangleMesh& mesh, const Vector3d& min, const Vector3d& max, double tolerance = 1e-12) {
  const BoundingBox box = bounding_box(mesh);
  REQUIRE_FALSE(box.empty());
  INFO("min = " << box.min.transpose() << ", max = " << box.max.transpose());
  CHECK((box.min - min).cwiseAbs().maxCoeff() < tolerance);
  CHECK((box.max - max).cwiseAbs().maxCoeff() < tolerance);
}

Vector3d triangle_normal2(const TriangleMesh& mesh, const std::array<int, 3>& t) {
  const Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
  const Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
  const Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
  return (b - a).cross(c - a);
}

/// Area of the regular n-gon inscribed in a circle of radius r: n triangles with apex angle
/// 2 pi / n, each of area r^2 sin(2 pi / n) / 2.
double ngon_area(int n, double r) { return n / 2.0 * r * r * std::sin(2 * kPi / n); }

/// Volume of the polyhedron inscribed in a sphere of radius r with `bands` latitude bands
/// (polar angles k pi / bands) and n longitudes, as MeshGenerator builds it. Between two
/// rings the vertices sit at the same longitudes, so each side quad is a planar trapezoid and
/// each band is a frustum of a regular n-gonal pyramid:
///   V = d / 3 (A1 + A2 + sqrt(A1 A2)) with A = ngon_area(n, rho), rho = r sin(polar),
/// d = height of the band. The polar caps are pyramids (A = 0).
double inscribed_sphere_volume(double r, int bands, int n) {
  double volume = 0;
  for (int k = 0; k < bands; ++k) {
    const double t0 = k * kPi / bands, t1 = (k + 1) * kPi / bands;
    const double a0 = ngon_area(n, r * std::sin(t0)), a1 = ngon_area(n, r * std::sin(t1));
    const double d = r * (std::cos(t0) - std::cos(t1));
    volume += d / 3 * (a0 + a1 + std::sqrt(a0 * a1));
  }
  return volume;
}

double relative_error(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

Extrusion simple_tank_track() {
  Extrusion e;
  e.cross_section = {{-0.34, 0.06}, {-0.22, -0.1}, {0.22, -0.1}, {0.34, 0.06}, {-0.34, 0.06}};
  e.spine = {{0, -0.05, 0}, {0, 0.05, 0}};
  return e;
}

bool has_error(const CollectingSink& sink, const char* rule) {
  for (const Diagnostic& d : sink.diagnostics()) {
    if (d.rule_id == rule && d.severity == Severity::kError && d.location == kWhere) return true;
  }
  return false;
}

}  // namespace

// --------------------------------------------------------------------------------------------
// Primitives

TEST_CASE("tessellate: box is centred with full edge lengths and its exact volume") {
  CollectingSink sink;
  const TriangleMesh m = run(Box{Vector3d(0.45, 0.3, 0.1)}, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(m.vertices.size() == 8);
  CHECK(m.triangles.size() == 12);
  check_box(m, Vector3d(-0.225, -0.15, -0.05), Vector3d(0.225, 0.15, 0.05));
  CHECK(signed_volume(m) == doctest::Approx(0.45 * 0.3 * 0.1).epsilon(1e-13));
  CHECK(closed_and_consistent(m));
}

TEST_CASE("tessellate: box with a zero edge is allowed and flat") {
  CollectingSink sink;
  const TriangleMesh m = run(Box{Vector3d(1, 0, 2)}, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(signed_volume(m) == doctest::Approx(0.0));
}

TEST_CASE("tessellate: cylinder runs along +Y and is the inscribed prism") {
  CollectingSink sink;
  const TriangleMesh m = run(Cylinder{0.1, 0.1, true, true}, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(m.vertices.size() == 2 * 20 + 2);
  CHECK(m.triangles.size() == 4 * 20);
  // SimpleTank's turret-P cylinder: n = 20 is a multiple of 4, so vertices lie on +-X and +-Z.
  check_box(m, Vector3d(-0.1, -0.05, -0.1), Vector3d(0.1, 0.05, 0.1));
  // Vertex 0 is at angle 0 on +X, vertex 5 at 90 degrees on +Z (r cos a, y, r sin a).
  CHECK((m.vertices[0] - Vector3d(0.1, 0.05, 0)).norm() < 1e-15);
  CHECK((m.vertices[5] - Vector3d(0, 0.05, 0.1)).norm() < 1e-15);
  // Prism over the inscribed 20-gon: n/2 r^2 sin(2 pi / n) h.
  const double prism = ngon_area(20, 0.1) * 0.1;
  CHECK(signed_volume(m) == doctest::Approx(prism).epsilon(1e-12));
  // n sin(2 pi / n) / (2 pi) = 0.9836 for n = 20: 1.6 % below the smooth cylinder.
  CHECK(relative_error(signed_volume(m), kPi * 0.01 * 0.1) < 0.02);
  CHECK(closed_and_consistent(m));
}

TEST_CASE("tessellate: cylinder without caps is open") {
  CollectingSink sink;
  const TriangleMesh m = run(Cylinder{1, 2, false, false}, 16, sink);
  CHECK(m.triangles.size() == 2 * 16);
  CHECK_FALSE(closed_and_consistent(m));
  const TriangleMesh top_only = run(Cylinder{1, 2, true, false}, 16, sink);
  CHECK(top_only.triangles.size() == 3 * 16);
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("tessellate: cone has its base at -h/2 and apex at +h/2") {
  CollectingSink sink;
  const TriangleMesh m = run(Cone{0.5, 2, true}, 24, sink);
  CHECK(sink.diagnostics().empty());
  check_box(m, Vector3d(-0.5, -1, -0.5), Vector3d(0.5, 1, 0.5));
  CHECK((m.vertices[24] - Vector3d(0, 1, 0)).norm() < 1e-15);  // apex
  // Pyramid over the inscribed 24-gon: A h / 3.
  const double pyramid = ngon_area(24, 0.5) * 2 / 3;
  CHECK(signed_volume(m) == doctest::Approx(pyramid).epsilon(1e-12));
  CHECK(relative_error(signed_volume(m), kPi * 0.25 * 2 / 3) < 0.02);
  CHECK(closed_and_consistent(m));

  const TriangleMesh open = run(Cone{0.5, 2, false}, 24, sink);
  CHECK(open.triangles.size() == 24);
  CHECK_FALSE(closed_and_consistent(open));
}

TEST_CASE("tessellate: sphere is the inscribed polyhedron with n longitudes, n/2 bands") {
  CollectingSink sink;
  for (int n : {20, 13, 4, 64}) {
    CAPTURE(n);
    const TriangleMesh m = run(Sphere{0.3}, n, sink);
    const int bands = n / 2;
    CHECK(m.vertices.size() == static_cast<std::size_t>((bands - 1) * n + 2));
    CHECK(m.triangles.size() == static_cast<std::size_t>(2 * bands * n - 2 * n));
    CHECK(signed_volume(m) == doctest::Approx(inscribed_sphere_volume(0.3, bands, n)).epsilon(1e-12));
    CHECK(closed_and_consistent(m));
  }
  // Default division: 4.8 % below the smooth sphere (latitude bands of 18 degrees).
  const TriangleMesh m = run(Sphere{0.3}, 20, sink);
  CHECK(relative_error(signed_volume(m), 4.0 / 3 * kPi * 0.027) < 0.05);
  // n = 20: 10 bands, so the equator is a ring and the box is exact.
  check_box(m, Vector3d(-0.3, -0.3, -0.3), Vector3d(0.3, 0.3, 0.3));
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("tessellate: capsule height is the cylindrical part, caps are hemispheres") {
  CollectingSink sink;
  const double r = 0.1, h = 0.2;
  const TriangleMesh m = run(Capsule{r, h}, 20, sink);
  CHECK(sink.diagnostics().empty());
  check_box(m, Vector3d(-r, -h / 2 - r, -r), Vector3d(r, h / 2 + r, r));
  // Two hemispherical polyhedra (10 bands, split at the equator) pulled apart by a prism.
  const double expected = inscribed_sphere_volume(r, 10, 20) + ngon_area(20, r) * h;
  CHECK(signed_volume(m) == doctest::Approx(expected).epsilon(1e-12));
  CHECK(relative_error(signed_volume(m), 4.0 / 3 * kPi * r * r * r + kPi * r * r * h) < 0.05);
  CHECK(closed_and_consistent(m));

  // n = 10 gives 5 bands, rounded up to 6 so that the equator is a ring (MeshGenerator).
  const TriangleMesh odd = run(Capsule{r, h}, 10, sink);
  const double expected_odd = inscribed_sphere_volume(r, 6, 10) + ngon_area(10, r) * h;
  CHECK(signed_volume(odd) == doctest::Approx(expected_odd).epsilon(1e-12));
  CHECK(closed_and_consistent(odd));

  // Height 0 is allowed: a sphere.
  const TriangleMesh ball = run(Capsule{r, 0}, 20, sink);
  CHECK(signed_volume(ball) == doctest::Approx(inscribed_sphere_volume(r, 10, 20)).epsilon(1e-12));
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("tessellate: division_number below 4 means 20, huge values are clamped") {
  CollectingSink sink;
  for (int n : {-5, 0, 3}) {
    CAPTURE(n);
    CHECK(run(Cylinder{}, n, sink).vertices.size() == 42);
  }
  CHECK(effective_division_number(3) == 20);
  CHECK(effective_division_number(4) == 4);
  // n = 4: a square prism with corners on +-X and +-Z, volume 2 r^2 h.
  const TriangleMesh square = run(Cylinder{1, 1, true, true}, 4, sink);
  check_box(square, Vector3d(-1, -0.5, -1), Vector3d(1, 0.5, 1));
  CHECK(signed_volume(square) == doctest::Approx(2.0));
  CHECK(sink.diagnostics().empty());

  const TriangleMesh big = run(Cylinder{}, 1000000, sink);
  CHECK(big.vertices.size() == static_cast<std::size_t>(2 * kMaxDivisionNumber + 2));
  REQUIRE(sink.diagnostics().size() == 1);
  CHECK(sink.diagnostics()[0].severity == Severity::kWarning);
  // Boxes do not use the division number: no warning.
  sink.clear();
  run(Box{}, 1000000, sink);
  CHECK(sink.diagnostics().empty());
}

// --------------------------------------------------------------------------------------------
// Extrusion

TEST_CASE("tessellate: extrusion of SimpleTank's track is a trapezoidal prism") {
  CollectingSink sink;
  const TriangleMesh m = run(simple_tank_track(), 20, sink);
  CHECK(sink.diagnostics().empty());
  // Closed cross-section: 4 distinct points per spine point.
  CHECK(m.vertices.size() == 8);
  // Straight spine along +Y keeps X -> X and Z -> Z.
  check_box(m, Vector3d(-0.34, -0.05, -0.1), Vector3d(0.34, 0.05, 0.06));
  // Trapezoid: parallel sides 0.68 and 0.44, height 0.16 -> area 0.0896; width 0.1.
  CHECK(signed_volume(m) == doctest::Approx(0.0896 * 0.1).epsilon(1e-12));
  CHECK(closed_and_consistent(m));
}

TEST_CASE("tessellate: extrusion is outward whichever way the cross-section runs") {
  CollectingSink sink;
  Extrusion e = simple_tank_track();
  std::reverse(e.cross_section.begin(), e.cross_section.end());
  const TriangleMesh m = run(e, 20, sink);
  CHECK(signed_volume(m) == doctest::Approx(0.0896 * 0.1).epsilon(1e-12));
  CHECK(closed_and_consistent(m));
  // A spine running backwards (-Y) is a rigid turn of the same prism.
  Extrusion down = simple_tank_track();
  std::swap(down.spine[0], down.spine[1]);
  const TriangleMesh d = run(down, 20, sink);
  CHECK(signed_volume(d) == doctest::Approx(0.0896 * 0.1).epsilon(1e-12));
  CHECK(closed_and_consistent(d));
  // Open surface (no caps): triangles still face away from the cross-section's inside.
  Extrusion open = simple_tank_track();
  open.begin_cap = open.end_cap = false;
  std::reverse(open.cross_section.begin(), open.cross_section.end());
  const TriangleMesh o = run(open, 20, sink);
  CHECK(o.triangles.size() == 2 * 4);
  for (const auto& t : o.triangles) {
    const Vector3d centre = (o.vertices[t[0]] + o.vertices[t[1]] + o.vertices[t[2]]) / 3;
    const Vector3d outward(centre.x(), 0, centre.z() + 0.02);  // from inside the trapezoid
    CHECK(triangle_normal2(o, t).dot(outward) > 0);
  }
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("tessellate: extrusion along a collinear spine with a scale per point") {
  // Unit square (closed) swept along (0,0,0) -> (0,1,0) -> (0,2,0) with scale 1, 2, 1:
  // two frusta of square pyramids, each V = h/3 (A1 + A2 + sqrt(A1 A2)) = 1/3 (1 + 4 + 2).
  Extrusion e;
  e.cross_section = {{0.5, 0.5}, {0.5, -0.5}, {-0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
  e.spine = {{0, 0, 0}, {0, 1, 0}, {0, 2, 0}};
  e.scale = {{1, 1}, {2, 2}, {1, 1}};
  CollectingSink sink;
  const TriangleMesh m = run(e, 20, sink);
  CHECK(sink.diagnostics().empty());
  check_box(m, Vector3d(-1, 0, -1), Vector3d(1, 2, 1));
  CHECK(signed_volume(m) == doctest::Approx(14.0 / 3).epsilon(1e-12));
  CHECK(closed_and_consistent(m));
}

TEST_CASE("tessellate: extrusion spine along other directions turns the cross-section rigidly") {
  Extrusion e;
  e.cross_section = {{-0.5, -0.25}, {0.5, -0.25}, {0.5, 0.25}, {-0.5, 0.25}, {-0.5, -0.25}};
  CollectingSink sink;
  SUBCASE("+X: the rotation taking +Y to +X is -90 degrees about Z, so x -> -y, z -> z") {
    e.spine = {{0, 0, 0}, {2, 0, 0}};
    const TriangleMesh m = run(e, 20, sink);
    check_box(m, Vector3d(0, -0.5, -0.25), Vector3d(2, 0.5, 0.25));
    CHECK(signed_volume(m) == doctest::Approx(1.0).epsilon(1e-12));
  }
  SUBCASE("a diagonal spine keeps lengths (Choreonoid's unnormalised axis would not)") {
    e.spine = {{0, 0, 0}, {1, 1, 0}};
    const TriangleMesh m = run(e, 20, sink);
    CHECK(signed_volume(m) == doctest::Approx(0.5 * std::sqrt(2.0)).epsilon(1e-12));
    for (int k = 0; k < 4; ++k) {
      // Each cap edge keeps its length: the SCP is a rotation.
      const double edge =
          (m.vertices[static_cast<std::size_t>(k)] - m.vertices[static_cast<std::size_t>((k + 1) % 4)]).norm();
      CHECK(edge == doctest::Approx(k % 2 == 0 ? 1.0 : 0.5));
    }
  }
  SUBCASE("-Y: a proper rotation (Choreonoid builds a reflection here)") {
    e.spine = {{0, 0, 0}, {0, -3, 0}};
    const TriangleMesh m = run(e, 20, sink);
    check_box(m, Vector3d(-0.5, -3, -0.25), Vector3d(0.5, 0, 0.25));
    CHECK(signed_volume(m) == doctest::Approx(1.5).epsilon(1e-12));
    CHECK(closed_and_consistent(m));
  }
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("tessellate: ExtrusionFrames::kChoreonoid keeps Choreonoid's matrices for collinear spines") {
  CollectingSink sink;
  auto as_choreonoid = [&](const Extrusion& e) {
    return tessellate(Geometry{e}, 20, sink, kWhere, ExtrusionFrames::kChoreonoid);
  };
  SUBCASE("+Y, +X and -Z: the unnormalised axis has length 1 or 0, so both modes give the same vertices") {
    for (const Vector3d& end : {Vector3d(0, 0.05, 0), Vector3d(0.3, -0.05, 0), Vector3d(0, -0.05, -0.2)}) {
      Extrusion e = simple_tank_track();
      e.spine[1] = end;
      const TriangleMesh rigid = run(e, 20, sink), skewed = as_choreonoid(e);
      REQUIRE(rigid.vertices.size() == skewed.vertices.size());
      for (std::size_t k = 0; k < rigid.vertices.size(); ++k)
        CHECK((rigid.vertices[k] - skewed.vertices[k]).norm() < 1e-15);
    }
  }
  SUBCASE("a spine along (1, 1, 0)/sqrt(2): the section is shrunk, not rotated") {
    // y = (s, s, 0) with s = 1/sqrt(2): angle 45 degrees, cos = sin = s, a = (0, 0, -s).
    // M = s I + (1 - s) a a^T + s [a]x = [[s, 1/2, 0], [-1/2, s, 0], [0, 0, s + (1 - s)/2]],
    // so (x, 0, 0) -> x (s, -1/2, 0), of length x sqrt(3)/2 (a rotation would keep x), and
    // (0, 0, z) -> z (0, 0, s + (1 - s)/2).
    Extrusion e;
    e.cross_section = {{-0.5, -0.25}, {0.5, -0.25}, {0.5, 0.25}, {-0.5, 0.25}, {-0.5, -0.25}};
    e.spine = {{0, 0, 0}, {1, 1, 0}};
    const TriangleMesh m = as_choreonoid(e);
    REQUIRE(m.vertices.size() == 8);
    const double s = 1 / std::sqrt(2.0);
    CHECK((m.vertices[1] - m.vertices[0]).norm() == doctest::Approx(std::sqrt(3.0) / 2).epsilon(1e-12));
    CHECK((m.vertices[2] - m.vertices[1]).norm() == doctest::Approx(0.5 * (s + (1 - s) / 2)).epsilon(1e-12));
    CHECK(closed_and_consistent(m));
  }
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("tessellate: torus-like extrusion with orientation and scale lists") {
  // Spine: a closed regular N-gon of radius R in the XZ plane (last point = first). At each
  // spine point the SCP has Y along the tangent and Z along the world Y axis (perpendicular to
  // the spine plane), so the cross-section lies in the radial half-plane. Every spine point
  // gets scale 0.5 and a 45 degree turn about the SCP Y axis, turning the 0.4 square into a
  // diamond with half-diagonal 0.1 sqrt(2), corners along the radial and vertical axes.
  //
  // Volume: between spine angles 0 and a, the point (rho, w) of the cross-section moves on the
  // chord rho ((1 - t) e0 + t e1) + w Y. The side quads are planar trapezoids (both chords
  // are parallel to e1 - e0), and the Jacobian of (rho, w, t) -> point is rho sin a, so each
  // wedge has volume sin a * integral(rho dA) = sin a * A * rho_centroid. In total
  //   V = N sin(2 pi / N) A R,   with A = 0.2^2 = 0.04.
  // (Pappus' smooth torus would have 2 pi instead of N sin(2 pi / N).)
  const int N = 16;
  const double R = 1.0;
  Extrusion e;
  for (int i = 0; i <= N; ++i) {
    const double a = 2 * kPi * (i % N) / N;
    e.spine.emplace_back(R * std::cos(a), 0, R * std::sin(a));
    e.scale.emplace_back(0.5, 0.5);
    e.orientation.emplace_back(kPi / 4, Vector3d::UnitY());
  }
  e.cross_section = {{0.2, 0.2}, {0.2, -0.2}, {-0.2, -0.2}, {-0.2, 0.2}, {0.2, 0.2}};
  CollectingSink sink;
  const TriangleMesh m = run(e, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(m.vertices.size() == static_cast<std::size_t>(N * 4));
  CHECK(m.triangles.size() == static_cast<std::size_t>(N * 4 * 2));  // no caps: closed spine
  CHECK(closed_and_consistent(m));
  const double d = 0.1 * std::sqrt(2.0);
  check_box(m, Vector3d(-R - d, -d, -R - d), Vector3d(R + d, d, R + d));
  CHECK(signed_volume(m) == doctest::Approx(N * std::sin(2 * kPi / N) * 0.04 * R).epsilon(1e-12));
  CHECK(relative_error(signed_volume(m), 2 * kPi * 0.04 * R) < 0.03);
}

TEST_CASE("tessellate: extrusion that tapers to a point omits the collapsed cap silently") {
  // Scale 0 at the end: a square pyramid of base 1 and height 1, V = 1/3.
  Extrusion e;
  e.cross_section = {{0.5, 0.5}, {0.5, -0.5}, {-0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
  e.spine = {{0, 0, 0}, {0, 1, 0}};
  e.scale = {{1, 1}, {0, 0}};
  CollectingSink sink;
  const TriangleMesh m = run(e, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(signed_volume(m) == doctest::Approx(1.0 / 3).epsilon(1e-12));
}

TEST_CASE("tessellate: extrusion with an open cross-section and caps off") {
  Extrusion e;
  e.cross_section = {{0, 0}, {1, 0}, {1, 1}};  // not closed: 2 side strips
  e.spine = {{0, 0, 0}, {0, 1, 0}, {0, 2, 0}};
  e.begin_cap = e.end_cap = false;
  CollectingSink sink;
  const TriangleMesh m = run(e, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(m.vertices.size() == 9);
  CHECK(m.triangles.size() == 2 * 2 * 2);
  CHECK_FALSE(closed_and_consistent(m));
}

// --------------------------------------------------------------------------------------------
// ElevationGrid

TEST_CASE("tessellate: elevation grid vertices, orientation and volume under the surface") {
  // Heights of the plane y = 1 + 0.2 x - 0.1 z on a 4 x 3 grid with spacings 0.5 and 2.
  // The triangulated surface is that plane exactly, so the volume between it and y = 0 over
  // [0, 1.5] x [0, 4] is X Z (1 + 0.2 X / 2 - 0.1 Z / 2) = 6 * 0.95 = 5.7.
  ElevationGrid g;
  g.x_dimension = 4;
  g.z_dimension = 3;
  g.x_spacing = 0.5;
  g.z_spacing = 2;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) g.height.push_back(1 + 0.2 * i * 0.5 - 0.1 * j * 2);
  CollectingSink sink;
  const TriangleMesh m = run(g, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(m.vertices.size() == 12);
  CHECK(m.triangles.size() == 2 * 3 * 2);
  // Vertex (i, j) at (i xs, h[j xd + i], j zs).
  CHECK((m.vertices[4 * 2 + 3] - Vector3d(1.5, g.height[11], 4)).norm() < 1e-15);
  check_box(m, Vector3d(0, 0.6, 0), Vector3d(1.5, 1.3, 4));
  // Prism under each triangle: (projected area, signed by the +Y normal) x (mean height).
  double volume = 0;
  for (const auto& t : m.triangles) {
    const Vector3d n2 = triangle_normal2(m, t);
    CHECK(n2.y() > 0);  // ccw: the top faces +Y
    volume += n2.y() / 2 * (m.vertices[t[0]].y() + m.vertices[t[1]].y() + m.vertices[t[2]].y()) / 3;
  }
  CHECK(volume == doctest::Approx(5.7).epsilon(1e-12));

  g.ccw = false;
  const TriangleMesh down = run(g, 20, sink);
  for (const auto& t : down.triangles) CHECK(triangle_normal2(down, t).y() < 0);
}

// --------------------------------------------------------------------------------------------
// IndexedFaceSet and TriangleMesh geometry

namespace {

// A U shape (area 3 x 2 - 1 x 1 = 5). A fan from vertex 0 would produce the clockwise
// triangle (0,0) (2,2) (2,1), so only a real triangulation gets every triangle right.
const std::vector<Vector2d> kUShape = {{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

}  // namespace

TEST_CASE("tessellate: indexed face set triangulates a concave polygon in any plane") {
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const Eigen::Matrix3d& r : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), rotation}) {
    IndexedFaceSet f;
    for (const Vector2d& p : kUShape) f.vertices.push_back(r * Vector3d(p.x(), p.y(), 0.3));
    for (int i = 0; i < 8; ++i) f.faces.push_back(i);
    f.faces.push_back(-1);
    CollectingSink sink;
    const TriangleMesh m = run(f, 20, sink);
    CHECK(sink.diagnostics().empty());
    REQUIRE(m.triangles.size() == 6);
    double area = 0;
    const Vector3d normal = r * Vector3d::UnitZ();
    for (const auto& t : m.triangles) {
      const Vector3d n2 = triangle_normal2(m, t);
      CHECK(n2.dot(normal) > 0);  // same winding as the polygon
      area += n2.norm() / 2;
    }
    CHECK(area == doctest::Approx(5.0).epsilon(1e-12));
  }
}

TEST_CASE("tessellate: indexed face set cube of quads, a last polygon without -1 is dropped") {
  IndexedFaceSet f;
  for (int k = 0; k < 8; ++k) f.vertices.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  f.faces = {0, 2, 3, 1, -1, 4, 5, 7, 6, -1, 0, 1, 5, 4, -1, 2, 6, 7, 3, -1, 0, 4, 6, 2, -1, 1, 3, 7, 5, -1};
  CollectingSink sink;
  const TriangleMesh m = run(f, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(m.triangles.size() == 12);
  CHECK(signed_volume(m) == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(closed_and_consistent(m));

  f.faces.pop_back();  // "1 3 7 5" without its -1: Choreonoid drops it without a message
  const TriangleMesh open = run(f, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(open.triangles.size() == 10);
}

TEST_CASE("tessellate: triangle mesh geometry keeps the triangles as given") {
  TriangleMeshGeometry g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  g.faces = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  CollectingSink sink;
  const TriangleMesh m = run(g, 20, sink);
  CHECK(sink.diagnostics().empty());
  CHECK(m.triangles.size() == 4);
  CHECK(signed_volume(m) == doctest::Approx(1.0 / 6).epsilon(1e-14));
  CHECK(closed_and_consistent(m));
}

TEST_CASE("tessellate: mesh resource gives an empty mesh without diagnostics") {
  CollectingSink sink;
  MeshResource r;
  r.uri = "tank.wrl";
  CHECK(run(r, 20, sink).empty());
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("tessellate: the Shape overload uses the shape's division number and location") {
  Shape s;
  s.geometry = Sphere{-1};
  s.division_number = 8;
  s.source = kWhere;
  CollectingSink sink;
  CHECK(tessellate(s, sink).empty());
  CHECK(has_error(sink, "geometry-invalid-size"));
  s.geometry = Cylinder{};
  CHECK(tessellate(s, sink).vertices.size() == 18);
}

// --------------------------------------------------------------------------------------------
// Invalid input: one diagnostic with the right rule, at the shape's location; no crash.

TEST_CASE("tessellate: invalid sizes are reported as geometry-invalid-size") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::pair<const char*, Geometry>> cases = {
      {"negative box", Box{Vector3d(1, -0.1, 1)}},
      {"NaN box", Box{Vector3d(nan, 1, 1)}},
      {"zero sphere", Sphere{0}},
      {"negative sphere", Sphere{-1}},
      {"NaN sphere", Sphere{nan}},
      {"zero cylinder radius", Cylinder{0, 1, true, true}},
      {"negative cylinder height", Cylinder{1, -1, true, true}},
      {"zero cylinder height", Cylinder{1, 0, true, true}},
      {"zero cone height", Cone{1, 0, true}},
      {"negative cone radius", Cone{-1, 1, true}},
      {"zero capsule radius", Capsule{0, 1}},
      {"negative capsule height", Capsule{1, -0.1}},
  };
  Extrusion one_cs = simple_tank_track();
  one_cs.cross_section.resize(1);
  cases.emplace_back("extrusion with 1 cross-section point", one_cs);
  Extrusion one_spine = simple_tank_track();
  one_spine.spine.resize(1);
  cases.emplace_back("extrusion with 1 spine point", one_spine);
  Extrusion orientations = simple_tank_track();
  orientations.spine.emplace_back(0, 0.2, 0);
  orientations.orientation.assign(2, Eigen::AngleAxisd(0, Vector3d::UnitY()));
  cases.emplace_back("2 orientations for 3 spine points", orientations);
  Extrusion scales = simple_tank_track();
  scales.scale.assign(3, Vector2d(1, 1));
  cases.emplace_back("3 scales for 2 spine points", scales);
  ElevationGrid grid;
  grid.x_dimension = 3;
  grid.z_dimension = 3;
  grid.height.assign(8, 0.0);
  cases.emplace_back("8 heights for 3 x 3", grid);
  ElevationGrid negative_grid;
  negative_grid.x_dimension = -2;
  negative_grid.z_dimension = -2;
  negative_grid.height.assign(4, 0.0);
  cases.emplace_back("negative grid dimensions", negative_grid);

  for (const auto& test_case : cases) {
    const auto& name = test_case.first;  // not a structured binding: CAPTURE needs a variable
    const auto& geometry = test_case.second;
    CAPTURE(name);
    CollectingSink sink;
    const TriangleMesh m = run(geometry, 20, sink);
    CHECK(m.empty());
    CHECK(sink.diagnostics().size() == 1);
    CHECK(has_error(sink, "geometry-invalid-size"));
  }
}

TEST_CASE("tessellate: degenerate geometry is reported as geometry-degenerate") {
  std::vector<std::pair<const char*, Geometry>> cases;
  Extrusion same = simple_tank_track();
  same.spine = {{1, 1, 1}, {1, 2, 1}, {1, 1, 1}};  // closes to 2 points: allowed (flat)
  Extrusion coincident = simple_tank_track();
  coincident.spine = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};  // closes to 2 identical points
  cases.emplace_back("coincident spine", coincident);
  Extrusion closing = simple_tank_track();
  closing.cross_section = {{0, 0}, {0, 0}};  // closes to a single point
  cases.emplace_back("cross-section of one point after closing", closing);
  ElevationGrid line;
  line.x_dimension = 5;
  line.z_dimension = 1;
  line.height.assign(5, 0.0);
  cases.emplace_back("1-row elevation grid", line);
  IndexedFaceSet two_points;
  two_points.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  two_points.faces = {0, 1, -1};
  cases.emplace_back("2-point polygon", two_points);
  IndexedFaceSet collinear = two_points;
  collinear.faces = {0, 1, 2, -1};
  cases.emplace_back("collinear polygon", collinear);
  IndexedFaceSet repeated = two_points;
  repeated.faces = {1, 1, 1, 1, -1};
  cases.emplace_back("repeated index", repeated);
  IndexedFaceSet no_faces = two_points;
  no_faces.faces = {};
  cases.emplace_back("no polygon", no_faces);
  IndexedFaceSet unterminated = two_points;
  unterminated.vertices.emplace_back(0, 1, 0);
  unterminated.faces = {0, 1, 3};  // the only polygon lacks -1: dropped, nothing left
  cases.emplace_back("only an unterminated polygon", unterminated);
  TriangleMeshGeometry leftover;
  leftover.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  leftover.faces = {0, 1, 2, 0, 1};
  cases.emplace_back("5 triangle indices", leftover);

  for (const auto& test_case : cases) {
    const auto& name = test_case.first;  // not a structured binding: CAPTURE needs a variable
    const auto& geometry = test_case.second;
    CAPTURE(name);
    CollectingSink sink;
    run(geometry, 20, sink);
    CHECK(sink.diagnostics().size() == 1);
    CHECK(has_error(sink, "geometry-degenerate"));
  }

  CollectingSink sink;
  run(same, 20, sink);
  CHECK(sink.diagnostics().empty());
}

TEST_CASE("tessellate: bad face indices are reported as geometry-index-out-of-range") {
  IndexedFaceSet f;
  f.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  f.faces = {0, 2, 1, -1, 0, 1, 4, -1, 0, -2, 3, -1, 1, 2, 3, -1};
  CollectingSink sink;
  const TriangleMesh m = run(f, 20, sink);
  // The two good polygons survive: a partial mesh.
  CHECK(m.triangles.size() == 2);
  CHECK(sink.diagnostics().size() == 2);
  CHECK(has_error(sink, "geometry-index-out-of-range"));
  CHECK(sink.error_count() == 2);

  TriangleMeshGeometry t;
  t.vertices = f.vertices;
  t.faces = {0, 2, 1, 0, 1, 7, -1, 1, 2};
  sink.clear();
  const TriangleMesh tm = run(t, 20, sink);
  CHECK(tm.triangles.size() == 1);
  CHECK(sink.diagnostics().size() == 2);
  CHECK(has_error(sink, "geometry-index-out-of-range"));
}

TEST_CASE("tessellate: a flood of bad polygons gives a bounded number of diagnostics") {
  IndexedFaceSet f;
  f.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int k = 0; k < 10000; ++k) f.faces.insert(f.faces.end(), {0, 1, 99, -1});
  CollectingSink sink;
  const TriangleMesh m = run(f, 20, sink);
  CHECK(m.empty());
  REQUIRE(sink.diagnostics().size() == 11);
  CHECK(sink.diagnostics().back().severity == Severity::kNote);
  CHECK(sink.diagnostics().back().rule_id == "geometry-more-problems");
  CHECK(sink.diagnostics().back().message.find("geometry-index-out-of-range") != std::string::npos);
  CHECK(sink.diagnostics().back().message.find("9990") != std::string::npos);
}

// --------------------------------------------------------------------------------------------
// triangulate_polygon

TEST_CASE("tessellate: triangulate_polygon handles duplicates, flat and self-intersecting input") {
  std::vector<Vector3d> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  std::vector<std::array<int, 3>> tris;
  // Repeated points (consecutive and wrapping) are skipped: a square, 2 triangles.
  CHECK(triangulate_polygon(v, {0, 0, 1, 2, 2, 3, 0}, tris));
  CHECK(tris.size() == 2);
  // Collinear: no area.
  tris.clear();
  CHECK_FALSE(triangulate_polygon(v, {0, 1, 4}, tris));
  CHECK(tris.empty());
  // A point on an edge (0 -> 4 passes through 1) is fine.
  tris.clear();
  CHECK(triangulate_polygon(v, {0, 1, 4, 2, 3}, tris));
  for (const auto& t : tris) {
    const Vector3d n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
    CHECK(n.z() >= 0);
  }
  // A symmetric bow tie: its two lobes cancel, no net area.
  tris.clear();
  CHECK_FALSE(triangulate_polygon(v, {0, 2, 1, 3}, tris));
  // An asymmetric self-intersecting polygon: no proper ear exists, yet it terminates and
  // covers it with at most n - 2 triangles.
  std::vector<Vector3d> w = {{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 1, 0}, {-1, 3, 0}};
  tris.clear();
  CHECK(triangulate_polygon(w, {0, 1, 2, 3, 4}, tris));
  CHECK(tris.size() >= 1);
  CHECK(tris.size() <= 3);
}

// --------------------------------------------------------------------------------------------
// Normals

TEST_CASE("tessellate: with_vertex_normals splits vertices at creases") {
  CollectingSink sink;
  const TriangleMesh box = run(Box{Vector3d(1, 2, 3)}, 20, sink);
  const TriangleMesh flat = with_vertex_normals(box, 0);
  // Each corner touches three faces with different normals: 8 x 3 vertices.
  CHECK(flat.vertices.size() == 24);
  REQUIRE(flat.normals.size() == 24);
  CHECK(flat.triangles.size() == 12);
  CHECK(signed_volume(flat) == doctest::Approx(6.0));
  for (const auto& t : flat.triangles) {
    const Vector3d n = triangle_normal2(flat, t).normalized();
    for (int i : t) CHECK((flat.normals[static_cast<std::size_t>(i)] - n).norm() < 1e-12);
    // Axis-aligned and pointing away from the centre.
    CHECK(n.cwiseAbs().maxCoeff() == doctest::Approx(1.0));
    CHECK(n.dot(flat.vertices[static_cast<std::size_t>(t[0])]) > 0);
  }

  // Sphere, everything smoothed: no split, normals close to radial.
  const TriangleMesh sphere = run(Sphere{2}, 20, sink);
  const TriangleMesh smooth = with_vertex_normals(sphere, kPi);
  CHECK(smooth.vertices.size() == sphere.vertices.size());
  for (std::size_t i = 0; i < smooth.vertices.size(); ++i) {
    CHECK(smooth.normals[i].dot(smooth.vertices[i].normalized()) > 0.99);
  }

  // Cylinder with Choreonoid's crease angle pi/2: the 90 degree cap edges stay sharp, the
  // 18 degree side edges are smoothed. Side ring vertices split in two (side + cap), the cap
  // centres stay single: 2 n x 2 + 2.
  const TriangleMesh cylinder = run(Cylinder{1, 1, true, true}, 20, sink);
  const TriangleMesh creased = with_vertex_normals(cylinder, kPi / 2);
  CHECK(creased.vertices.size() == 2 * 20 * 2 + 2);
  for (std::size_t i = 0; i < creased.vertices.size(); ++i) {
    const Vector3d& n = creased.normals[i];
    const bool cap = std::abs(std::abs(n.y()) - 1) < 1e-12;
    const bool side = std::abs(n.y()) < 1e-12;
    const bool cap_or_side = cap || side;
    CHECK(cap_or_side);
  }
  CHECK(sink.diagnostics().empty());
}
