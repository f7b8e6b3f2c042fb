// Mass properties from shapes (issue 39). The expected values are textbook closed forms worked
// out by hand in the comments (never read back from the code under test), the divergence
// theorem's exactness on polyhedra, and the convergence of fine tessellations to the closed
// forms (the tessellator is a separate path: it never sees the formulas).

#include <bodyfmt/angles.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/geometry_mass.h>
#include <bodyfmt/load.h>
#include <bodyfmt/tessellate.h>

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using namespace bodyfmt;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

using bodyfmt::kPi;

Matrix3d diagonal(double x, double y, double z) { return Vector3d(x, y, z).asDiagonal(); }

double relative_error(const MassProperties& got, const MassProperties& want) {
  const double scale = want.inertia.cwiseAbs().maxCoeff();
  return std::max({std::abs(got.mass - want.mass) / want.mass,
                   (got.center_of_mass - want.center_of_mass).norm() / std::cbrt(want.mass),
                   (got.inertia - want.inertia).cwiseAbs().maxCoeff() / scale});
}

MassProperties tessellated(const Geometry& g, int division) {
  CollectingSink sink;
  const TriangleMesh mesh = tessellate(g, division, sink, SourceLocation{});
  REQUIRE(mesh_solidity(mesh).solid());
  return mesh_mass_properties(mesh);
}

Model load(const std::string& text, CollectingSink& sink) {
  LoadOptions options;
  options.load_meshes = false;
  auto model = load_body_string(text, "mass.body", options, sink);
  REQUIRE(model);
  return *model;
}

const char* kHeader = R"(format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
name: Mass
root_link: BASE
links:
  - name: BASE
    joint_type: free
)";

}  // namespace

TEST_CASE("geometry mass: closed forms of the primitives, worked by hand") {
  // Box 1 x 2 x 3: V = 6, Ixx = V(4 + 9)/12 = 6.5, Iyy = V(1 + 9)/12 = 5, Izz = V(1 + 4)/12 = 2.5.
  Box box;
  box.size = Vector3d(1, 2, 3);
  auto m = primitive_mass_properties(box);
  REQUIRE(m);
  CHECK(m->mass == doctest::Approx(6).epsilon(1e-15));
  CHECK((m->inertia - diagonal(6.5, 5, 2.5)).norm() < 1e-14);
  // Sphere r = 2: V = 32π/3, I = 2/5·V·4 = 256π/15.
  Sphere sphere;
  sphere.radius = 2;
  m = primitive_mass_properties(sphere);
  REQUIRE(m);
  CHECK(m->mass == doctest::Approx(32 * kPi / 3).epsilon(1e-15));
  CHECK((m->inertia - diagonal(1, 1, 1) * 256 * kPi / 15).norm() < 1e-12);
  // Cylinder r = 1, h = 2 along Y: V = 2π, Iyy = V/2 = π, Ixx = Izz = V(3 + 4)/12 = 7π/6.
  Cylinder cylinder;
  cylinder.radius = 1;
  cylinder.height = 2;
  m = primitive_mass_properties(cylinder);
  REQUIRE(m);
  CHECK(m->mass == doctest::Approx(2 * kPi).epsilon(1e-15));
  CHECK((m->inertia - diagonal(7 * kPi / 6, kPi, 7 * kPi / 6)).norm() < 1e-13);
  // Cone r = 1, h = 4, apex at +Y: V = 4π/3, centroid h/4 = 1 above the base at -2, so y = -1;
  // Iyy = 3/10·V = 2π/5, Ixx = V(3/20 + 3·16/80) = V·3/4 = π.
  Cone cone;
  cone.radius = 1;
  cone.height = 4;
  m = primitive_mass_properties(cone);
  REQUIRE(m);
  CHECK(m->mass == doctest::Approx(4 * kPi / 3).epsilon(1e-15));
  CHECK((m->center_of_mass - Vector3d(0, -1, 0)).norm() < 1e-15);
  CHECK((m->inertia - diagonal(kPi, 2 * kPi / 5, kPi)).norm() < 1e-13);
  // Capsule r = 1, h = 2: cylinder 2π, ball 4π/3, V = 10π/3; Iyy = 2π/2 + 2/5·4π/3 = π + 8π/15;
  // Ixx = 2π·7/12 + 4π/3·(2/5 + 1 + 3/4) = 7π/6 + 4π/3·43/20 = 7π/6 + 43π/15.
  Capsule capsule;
  capsule.radius = 1;
  capsule.height = 2;
  m = primitive_mass_properties(capsule);
  REQUIRE(m);
  CHECK(m->mass == doctest::Approx(10 * kPi / 3).epsilon(1e-15));
  CHECK((m->inertia - diagonal(7 * kPi / 6 + 43 * kPi / 15, kPi + 8 * kPi / 15, 7 * kPi / 6 + 43 * kPi / 15)).norm() <
        1e-13);
  // Open primitives bound no volume.
  cylinder.top = false;
  CHECK_FALSE(primitive_mass_properties(cylinder));
  cone.bottom = false;
  CHECK_FALSE(primitive_mass_properties(cone));
}

TEST_CASE("geometry mass: the divergence theorem is exact on a tessellated box, placed anywhere") {
  Box box;
  box.size = Vector3d(0.3, 0.2, 0.5);
  const MassProperties exact = *primitive_mass_properties(box);
  CHECK(relative_error(tessellated(box, 20), exact) < 1e-13);
  // Moved, rotated and scaled: the mesh placed vertex by vertex against the transformed closed form.
  Eigen::Affine3d X = Eigen::Affine3d::Identity();
  X.translate(Vector3d(1e3, -2, 0.5));
  X.rotate(Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()));
  X.scale(Vector3d(2, 0.5, 3));
  CollectingSink sink;
  TriangleMesh placed;
  append_mesh(placed, tessellate(box, 20, sink, SourceLocation{}), X);
  const MassProperties moved = transform_mass_properties(exact, X);
  // |det| = 3: the volume triples.
  CHECK(moved.mass == doctest::Approx(3 * 0.3 * 0.2 * 0.5).epsilon(1e-14));
  CHECK(relative_error(mesh_mass_properties(placed), moved) < 1e-9);
}

TEST_CASE("geometry mass: fine tessellations of the curved primitives converge to the closed forms") {
  Sphere sphere;
  sphere.radius = 0.3;
  Cylinder cylinder;
  cylinder.radius = 0.2;
  cylinder.height = 0.7;
  Cone cone;
  cone.radius = 0.25;
  cone.height = 0.4;
  Capsule capsule;
  capsule.radius = 0.1;
  capsule.height = 0.5;
  for (const Geometry& g : {Geometry(sphere), Geometry(cylinder), Geometry(cone), Geometry(capsule)}) {
    const MassProperties exact = *primitive_mass_properties(g);
    const double coarse = relative_error(tessellated(g, 64), exact);
    const double fine = relative_error(tessellated(g, 512), exact);
    INFO("geometry " << g.index() << ": error " << coarse << " at 64, " << fine << " at 512");
    // Inscribed polygons lose O((2π/n)²): 8 times the division, about 64 times less error
    // (the sphere's latitude bands: 7.2e-3 at 64, 1.1e-4 at 512).
    CHECK(fine < 2e-4);
    CHECK(fine < coarse / 30);
  }
}

TEST_CASE("geometry mass: parallel-axis combination of two offset cubes") {
  // Two unit cubes centred at x = ±1: V = 2, centre 0; Ixx = 2·(1/6), Iyy = Izz = 2·(1/6 + 1).
  CollectingSink sink;
  const Model model = load(std::string(kHeader) + R"(    mass: 1
    elements:
      - type: Transform
        translation: [1, 0, 0]
        elements:
          - type: Shape
            geometry: {type: Box, size: [1, 1, 1]}
      - type: Transform
        translation: [-1, 0, 0]
        rotation: [0, 0, 1, 90]
        elements:
          - type: Shape
            geometry: {type: Box, size: [1, 1, 1]}
)",
                           sink);
  const LinkGeometryMass g = link_geometry_mass(model, model.links[0], sink);
  CHECK(g.solids == 2);
  CHECK(g.volume.mass == doctest::Approx(2));
  CHECK(g.volume.center_of_mass.norm() < 1e-15);
  CHECK((g.volume.inertia - diagonal(1.0 / 3, 7.0 / 3, 7.0 / 3)).norm() < 1e-14);
  // At the written mass, 1 kg: half of each.
  const auto at_mass = geometry_at_mass(g, 1);
  REQUIRE(at_mass);
  CHECK((at_mass->inertia - diagonal(1.0 / 6, 7.0 / 6, 7.0 / 6)).norm() < 1e-14);
}

TEST_CASE("geometry mass: collision shapes, visual ones where there are none, and RigidBody elements") {
  CollectingSink sink;
  const Model model = load(std::string(kHeader) + R"(    mass: 1
    elements:
      - type: Visual
        elements:
          - type: Shape
            geometry: {type: Box, size: [10, 10, 10]}
      - type: Collision
        elements:
          - type: Shape
            geometry: {type: Box, size: [1, 2, 1]}
  - name: ARM
    parent: BASE
    joint_type: revolute
    joint_axis: Z
    elements:
      - type: Visual
        elements:
          - type: Shape
            geometry: {type: Box, size: [2, 1, 1]}
      - type: RigidBody
        center_of_mass: [0, 0, 3]
        mass: 2
        inertia: [0, 0, 0, 0, 0, 0, 0, 0, 0]
)",
                           sink);
  const LinkGeometryMass base = link_geometry_mass(model, model.links[0], sink);
  CHECK_FALSE(base.from_visual);
  CHECK(base.volume.mass == doctest::Approx(2));
  const LinkGeometryMass arm = link_geometry_mass(model, model.links[1], sink);
  CHECK(arm.from_visual);
  // 2 m³ of the box at 1 kg/m³ at the origin and the RigidBody's 2 kg at z = 3: centre z = 1.5,
  // Ixx = box 2·(1 + 1)/12 + 2·1.5² + 2·1.5² = 1/3 + 9.
  const auto arm_mass = link_mass_from_geometry(model.links[1], arm, 1.0);
  REQUIRE(arm_mass);
  CHECK(arm_mass->mass == doctest::Approx(4));
  CHECK((arm_mass->center_of_mass - Vector3d(0, 0, 1.5)).norm() < 1e-15);
  CHECK(arm_mass->inertia(0, 0) == doctest::Approx(1.0 / 3 + 9));
  CHECK(arm_mass->inertia(2, 2) == doctest::Approx(2 * (4 + 1) / 12.0));
}

TEST_CASE("geometry mass: a shell is not a solid and is reported at the shape") {
  CollectingSink sink;
  const Model model = load(std::string(kHeader) + R"(    mass: 1
    elements:
      - type: Shape
        geometry: {type: Cylinder, radius: 0.1, height: 0.2, top: false}
      - type: Shape
        geometry:
          type: IndexedFaceSet
          vertices: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]
          faces: [0, 2, 1, -1, 0, 1, 3, -1, 0, 3, 2, -1, 1, 2, 3, -1]
      - type: Shape
        geometry:
          type: IndexedFaceSet
          vertices: [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]
          faces: [0, 2, 1, -1, 0, 1, 3, -1, 0, 3, 2, -1, 1, 3, 2, -1]
)",
                           sink);
  CHECK(sink.diagnostics().empty());
  const LinkGeometryMass g = link_geometry_mass(model, model.links[0], sink);
  // The closed tetrahedron counts (V = 1/6); the open cylinder and the tetrahedron with one face
  // turned inward do not.
  CHECK(g.solids == 1);
  CHECK(g.left_out == 2);
  CHECK(g.volume.mass == doctest::Approx(1.0 / 6).epsilon(1e-15));
  CHECK((g.volume.center_of_mass - Vector3d(0.25, 0.25, 0.25)).norm() < 1e-15);
  REQUIRE(sink.diagnostics().size() == 2);
  CHECK(sink.diagnostics()[0].rule_id == "inertia-geometry-not-solid");
  CHECK(sink.diagnostics()[0].location.line == 11);  // the first `- type: Shape`
  CHECK(sink.diagnostics()[0].message.find("not closed") != std::string::npos);
  CHECK(sink.diagnostics()[1].location.line == 18);  // the third
  CHECK(sink.diagnostics()[1].message.find("not consistently oriented") != std::string::npos);
}

// The tutorial's SimpleTank (examples/simpletank.body), worked by hand at water's 1000 kg/m³.
// A RigidBody element's mass data is that of the shapes below it: TURRET_P's drum and gun
// (3 kg and 1 kg, written) are not weighed again from their cylinders; only the lamp's cone,
// below no RigidBody, is.
TEST_CASE("geometry mass: the tutorial tank by hand, each RigidBody's shapes counted once") {
  CollectingSink sink;
  const std::optional<Model> model = load_body(std::string(BODYFMT_EXAMPLES_DIR) + "/simpletank.body", {}, sink);
  REQUIRE(model);
  const auto link = [&](const char* name) -> const Link& {
    for (const Link& l : model->links)
      if (l.name == name) return l;
    FAIL("no link " << name);
    return model->links.front();
  };
  const auto from_geometry = [&](const Link& l) {
    const LinkGeometryMass g = link_geometry_mass(*model, l, sink);
    return std::pair(g, link_mass_from_geometry(l, g, 1000.0));
  };

  // CHASSIS: a box 0.45 x 0.3 x 0.1 = 0.0135 m³ -> 13.5 kg, Ixx = m (b² + c²) / 12.
  const auto [hull, chassis] = from_geometry(link("CHASSIS"));
  REQUIRE(chassis);
  CHECK(chassis->mass == doctest::Approx(13.5).epsilon(1e-12));
  CHECK(chassis->inertia(0, 0) == doctest::Approx(13.5 * (0.09 + 0.01) / 12).epsilon(1e-12));
  CHECK(chassis->inertia(1, 1) == doctest::Approx(13.5 * (0.2025 + 0.01) / 12).epsilon(1e-12));
  CHECK(chassis->inertia(2, 2) == doctest::Approx(13.5 * (0.2025 + 0.09) / 12).epsilon(1e-12));

  // TURRET_Y: its box is below the 4 kg RigidBody, which stays as written (CoM z = 0.025).
  const auto [base, turret_y] = from_geometry(link("TURRET_Y"));
  CHECK(base.solids == 0);
  CHECK(base.solids_in_rigid_bodies() == 1);
  REQUIRE(turret_y);
  CHECK(turret_y->mass == doctest::Approx(4).epsilon(1e-15));
  CHECK(turret_y->center_of_mass.z() == doctest::Approx(0.025).epsilon(1e-15));

  // TURRET_P: drum 3 kg at 0 + gun 1 kg at x = 0.2 (written) + the cone r 0.025, h 0.04:
  // V = π r² h / 3 = 2.6180e-5 m³ -> 0.026180 kg. Its centroid is h/4 = 0.01 from the base
  // towards the apex; the cone's axis (+Y) is turned by Rz(90) onto -X, so the centroid is at
  // (0.08 - 0.02 + 0.01, 0, 0.1) = (0.07, 0, 0.1) in the link frame.
  const double cone = 1000 * kPi * 0.025 * 0.025 * 0.04 / 3;
  const double total = 3 + 1 + cone;
  const auto [gear, turret_p] = from_geometry(link("TURRET_P"));
  CHECK(gear.solids == 1);
  CHECK(gear.solids_in_rigid_bodies() == 2);
  REQUIRE(turret_p);
  CHECK(turret_p->mass == doctest::Approx(total).epsilon(1e-12));
  CHECK(turret_p->center_of_mass.x() == doctest::Approx((1 * 0.2 + cone * 0.07) / total).epsilon(1e-12));
  CHECK(turret_p->center_of_mass.z() == doctest::Approx(cone * 0.1 / total).epsilon(1e-12));
  // Counted twice, the cylinders' 1000·π(0.1²·0.1 + 0.02²·0.2) = 3.393 kg would be added.
  CHECK(turret_p->mass < 4.1);

  // TRACK_L: a trapezoid (0.68 top, 0.44 bottom, 0.16 high) 0.1 wide: 0.00896 m³ -> 8.96 kg,
  // centroid h (2a + b) / (3 (a + b)) above the bottom at z = -0.1.
  const auto [outline, track] = from_geometry(link("TRACK_L"));
  REQUIRE(track);
  CHECK(track->mass == doctest::Approx(8.96).epsilon(1e-12));
  CHECK(track->center_of_mass.z() ==
        doctest::Approx(-0.1 + 0.16 * (2 * 0.68 + 0.44) / (3 * (0.68 + 0.44))).epsilon(1e-12));
  CHECK(sink.diagnostics().empty());
}

// Recomputing every part at its written mass: TURRET_Y's RigidBody (4 kg) gets its box's tensor,
// m (b² + c²) / 12 = 4 (0.04 + 0.01) / 12 = 1/60 about X and Y and 4 (0.04 + 0.04) / 12 about Z
// (written 0.1: six times too large), and TURRET_P's gun its cylinder's in its own frame, where
// the axis is Y (the Transform's Rz(90) turns it onto the link's X): axial m r² / 2 = 0.0002,
// transverse m (3r² + h²) / 12 = (0.0012 + 0.04) / 12.
TEST_CASE("geometry mass: RigidBody elements recomputed from the shapes below them, in their own frame") {
  CollectingSink sink;
  const std::optional<Model> model = load_body(std::string(BODYFMT_EXAMPLES_DIR) + "/simpletank.body", {}, sink);
  REQUIRE(model);
  const Link& turret_y = model->links[1];
  REQUIRE(turret_y.name == "TURRET_Y");
  const auto y = geometry_at_written_mass(turret_y, link_geometry_mass(*model, turret_y, sink));
  REQUIRE(y);
  CHECK_FALSE(y->link_keys);
  REQUIRE(y->rigid_bodies.size() == 1);
  const MassProperties& base = y->rigid_bodies[0].as_written;
  CHECK(base.mass == 4);
  CHECK(base.center_of_mass.norm() < 1e-15);
  CHECK((base.inertia - diagonal(1.0 / 60, 1.0 / 60, 4 * 0.08 / 12)).cwiseAbs().maxCoeff() < 1e-15);

  const Link& turret_p = model->links[2];
  REQUIRE(turret_p.name == "TURRET_P");
  const auto p = geometry_at_written_mass(turret_p, link_geometry_mass(*model, turret_p, sink));
  REQUIRE(p);
  REQUIRE(p->rigid_bodies.size() == 2);
  const RecomputedRigidBody& gun = p->rigid_bodies[1];
  const double transverse = (3 * 0.0004 + 0.04) / 12;
  CHECK((gun.as_written.inertia - diagonal(transverse, 0.0002, transverse)).cwiseAbs().maxCoeff() < 1e-15);
  CHECK((gun.as_written.center_of_mass).norm() < 1e-15);
  // In the link frame the axis is X, at the Transform's x = 0.2.
  CHECK((gun.in_link.inertia - diagonal(0.0002, transverse, transverse)).cwiseAbs().maxCoeff() < 1e-15);
  CHECK((gun.in_link.center_of_mass - Vector3d(0.2, 0, 0)).norm() < 1e-15);
}
