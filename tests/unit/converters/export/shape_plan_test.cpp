// converters/export: the shape plan every XML writer spells out. For each geometry kind and
// each set of target capabilities: primitive or mesh, the sizes and the placement after the
// +Y -> +Z turn (checked against points of the Body shape computed here), the losses and
// where they are reported.
#include <bodyfmt/converters/shape_plan.h>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "support/load_helpers.h"

#include <cmath>
#include <filesystem>
#include <string>

using namespace bodyfmt;
using namespace bodyfmt::converters;
using Kind = PlannedPiece::Kind;

namespace {

/// A URDF-like target: no capsule, zero box edges allowed, no hulls, no emission, mesh files
/// referenced as they are.
ShapeTarget urdf_like() {
  return {"URDF", false, 0, false, false, [](const MeshResource&) { return true; }};
}
/// A MuJoCo-like target: capsules, positive sizes only, convex-hull collision, emission, every
/// mesh converted.
ShapeTarget mjcf_like() { return {"MuJoCo", true, 1e-6, true, true, nullptr}; }

const std::string kMeshDir = (std::filesystem::path(BODYFMT_TEST_DATA_DIR) / "mesh").generic_string();

/// One link whose `elements:` are `elements` (indented by 6), planned for its first shape.
/// Line 9 of the loaded text is the first line of `elements`.
struct Planned {
  Planned(const std::string& elements, const ShapeTarget& target)
      : loaded(test::load_v2(R"(
name: T
links:
  - name: L
    joint_type: free
    mass: 1
    elements:
)" + elements)) {
    const Model& model = loaded.m();
    REQUIRE(!model.links[0].shapes.empty());
    CollectingSink sink;
    plan = plan_shape(model, 0, 0, target, sink);
    INFO(test::describe(sink.diagnostics()));
    CHECK(sink.diagnostics().empty());
  }
  const Shape& shape() const { return loaded.m().links[0].shapes[0]; }
  std::string losses() const {
    std::string out;
    for (const PlannedLoss& loss : plan.losses) out += loss.what + "\n";
    return out + test::describe(loaded.diagnostics);
  }
  const PlannedPiece& only_piece() const {
    REQUIRE(plan.pieces.size() == 1);
    return plan.pieces[0];
  }

  test::LoadResult loaded;
  ShapePlan plan;
};

/// A loss is reported at the shape's own line (by default the first line of `elements`).
void check_at_shape(const PlannedLoss& loss, int line = 9) {
  CHECK(loss.at.line == line);
  CHECK(loss.at.column > 0);
}

bool near(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm() < 1e-12; }

}  // namespace

TEST_CASE("shape plan: a box is a primitive of the scaled size in every target, placed as the shape") {
  for (const ShapeTarget& target : {urdf_like(), mjcf_like()}) {
    Planned p(R"(      - type: Transform
        translation: [1, 2, 3]
        rotation: [0, 0, 1, 90]
        scale: [2, 3, 4]
        elements:
          - {type: Shape, geometry: {type: Box, size: [0.1, 0.2, 0.3]}}
)",
              target);
    CHECK(p.plan.losses.empty());
    const PlannedPiece& box = p.only_piece();
    CHECK(box.kind == Kind::kBox);
    CHECK(near(box.size, Eigen::Vector3d(0.2, 0.6, 1.2)));
    CHECK(near(box.origin.translation(), Eigen::Vector3d(1, 2, 3)));
    // 90° about Z: the box's x edge lies along the link's +Y.
    CHECK(near(box.origin.linear() * Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()));
    CHECK(near(box.origin.linear() * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()));
  }
}

TEST_CASE("shape plan: a box with a zero edge is thickened and reported only where the target refuses zero sizes") {
  const std::string flat = "      - {type: Shape, geometry: {type: Box, size: [1, 2, 0]}}\n";
  Planned urdf(flat, urdf_like());
  CHECK(urdf.plan.losses.empty());
  CHECK(near(urdf.only_piece().size, Eigen::Vector3d(1, 2, 0)));

  Planned mjcf(flat, mjcf_like());
  CHECK(near(mjcf.only_piece().size, Eigen::Vector3d(1, 2, 2e-6)));
  REQUIRE(mjcf.plan.losses.size() == 1);
  const PlannedLoss& loss = mjcf.plan.losses[0];
  CHECK(loss.kind == LossKind::kGeometry);
  CHECK(loss.what.find("zero edge") != std::string::npos);
  CHECK(loss.hint.find("MuJoCo") == 0);
  check_at_shape(loss);
}

TEST_CASE("shape plan: a sheared box is a mesh with the shear baked in, and nothing is lost") {
  for (const ShapeTarget& target : {urdf_like(), mjcf_like()}) {
    // A scale in a rotated frame shears the box in the link frame.
    Planned p(R"(      - type: Transform
        scale: [1, 2, 1]
        elements:
          - type: Transform
            rotation: [0, 0, 1, 45]
            elements:
              - {type: Shape, geometry: {type: Box, size: [1, 1, 1]}}
)",
              target);
    CHECK(p.plan.losses.empty());
    const PlannedPiece& mesh = p.only_piece();
    CHECK(mesh.kind == Kind::kMesh);
    CHECK(mesh.key == "shape:0:0:baked");
    CHECK(mesh.origin.linear().isIdentity(0));
    CHECK(near(mesh.scale, Eigen::Vector3d::Ones()));
    // Baked: the corner (0.5, 0.5, 0.5) of the box is at Rz(45°) then y * 2 in the link frame.
    const Eigen::Vector3d corner(0, std::sqrt(2.0), 0.5);
    bool found = false;
    for (const Eigen::Vector3d& v : mesh.mesh->vertices) found = found || near(v, corner);
    CHECK(found);
  }
}

TEST_CASE("shape plan: a sphere is a primitive when uniformly scaled, else a mesh with a geometry loss") {
  for (const ShapeTarget& target : {urdf_like(), mjcf_like()}) {
    Planned uniform(R"(      - type: Transform
        scale: [3, 3, 3]
        elements:
          - {type: Shape, translation: [0, 1, 0], geometry: {type: Sphere, radius: 0.5}}
)",
                    target);
    CHECK(uniform.plan.losses.empty());
    CHECK(uniform.only_piece().kind == Kind::kSphere);
    CHECK(uniform.only_piece().radius == doctest::Approx(1.5).epsilon(1e-15));
    CHECK(near(uniform.only_piece().origin.translation(), Eigen::Vector3d(0, 3, 0)));

    Planned stretched(R"(      - type: Transform
        scale: [1, 1, 2]
        elements:
          - {type: Shape, geometry: {type: Sphere, radius: 0.5}}
)",
                      target);
    CHECK(stretched.only_piece().kind == Kind::kMesh);
    CHECK(stretched.only_piece().key == "shape:0:0");
    CHECK(near(stretched.only_piece().scale, Eigen::Vector3d(1, 1, 2)));
    REQUIRE(stretched.plan.losses.size() == 1);
    CHECK(stretched.plan.losses[0].kind == LossKind::kGeometry);
    CHECK(stretched.plan.losses[0].what.find("non-uniformly scaled") != std::string::npos);
    check_at_shape(stretched.plan.losses[0], 12);
  }
}

TEST_CASE("shape plan: a cylinder turns from the Body's +Y axis onto the target's +Z, its caps where the Body's are") {
  for (const ShapeTarget& target : {urdf_like(), mjcf_like()}) {
    // Scaled 2 across and 3 along its axis: still a cylinder, radius 0.2 and length 1.2.
    Planned p(R"(      - type: Transform
        translation: [1, 2, 3]
        rotation: [0, 0, 1, 30]
        elements:
          - type: Transform
            scale: [2, 3, 2]
            elements:
              - {type: Shape, geometry: {type: Cylinder, radius: 0.1, height: 0.4}}
)",
              target);
    CHECK(p.plan.losses.empty());
    const PlannedPiece& c = p.only_piece();
    CHECK(c.kind == Kind::kCylinder);
    CHECK(c.radius == doctest::Approx(0.2).epsilon(1e-15));
    CHECK(c.length == doctest::Approx(1.2).epsilon(1e-15));
    // The Body cylinder's axis is its +Y, turned 30° about Z: (-sin 30°, cos 30°, 0).
    const Eigen::Vector3d axis(-0.5, std::sqrt(3.0) / 2, 0);
    const Eigen::Vector3d centre(1, 2, 3);
    CHECK(near(c.origin.linear() * Eigen::Vector3d::UnitZ(), axis));
    // The target's cap centres (0, 0, ±length/2) are the Body's (0, ±height/2, 0).
    CHECK(near(c.origin * Eigen::Vector3d(0, 0, 0.6), centre + 0.6 * axis));
    CHECK(near(c.origin * Eigen::Vector3d(0, 0, -0.6), centre - 0.6 * axis));
    // A rim point is at the radius from the axis, in the plane of the cap.
    const Eigen::Vector3d rim = c.origin * Eigen::Vector3d(0.2, 0, 0.6) - (centre + 0.6 * axis);
    CHECK(rim.norm() == doctest::Approx(0.2));
    CHECK(std::abs(rim.dot(axis)) < 1e-12);
    CHECK(c.origin.linear().determinant() == doctest::Approx(1.0));
  }
}

TEST_CASE("shape plan: an open cylinder is written closed and reported with the target's name") {
  Planned urdf("      - {type: Shape, geometry: {type: Cylinder, radius: 1, height: 1, top: false}}\n", urdf_like());
  CHECK(urdf.only_piece().kind == Kind::kCylinder);
  REQUIRE(urdf.plan.losses.size() == 1);
  CHECK(urdf.plan.losses[0].kind == LossKind::kGeometry);
  CHECK(urdf.plan.losses[0].hint == "URDF cylinders are closed");
  check_at_shape(urdf.plan.losses[0]);
}

TEST_CASE("shape plan: a cylinder scaled across its axis unevenly is a mesh with a geometry loss") {
  for (const ShapeTarget& target : {urdf_like(), mjcf_like()}) {
    Planned p(R"(      - type: Transform
        scale: [1, 1, 2]
        elements:
          - {type: Shape, geometry: {type: Cylinder, radius: 0.1, height: 0.4}}
)",
              target);
    CHECK(p.only_piece().kind == Kind::kMesh);
    REQUIRE(p.plan.losses.size() == 1);
    CHECK(p.plan.losses[0].what.find("non-uniformly scaled Cylinder") != std::string::npos);
    check_at_shape(p.plan.losses[0], 12);
  }
}

TEST_CASE("shape plan: a capsule is a primitive where the target has one, turned onto +Z, else a mesh, no loss") {
  const std::string capsule = R"(      - type: Shape
        translation: [0, 0, 1]
        rotation: [1, 0, 0, 90]
        geometry: {type: Capsule, radius: 0.1, height: 0.5}
)";
  Planned mjcf(capsule, mjcf_like());
  CHECK(mjcf.plan.losses.empty());
  const PlannedPiece& c = mjcf.only_piece();
  CHECK(c.kind == Kind::kCapsule);
  CHECK(c.radius == doctest::Approx(0.1).epsilon(1e-15));
  CHECK(c.length == doctest::Approx(0.5).epsilon(1e-15));
  // Rx(90°) turns the Body's +Y onto +Z: the target's +Z stays +Z, and the end of the straight
  // part is 0.25 above the centre.
  CHECK(near(c.origin.linear() * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()));
  CHECK(near(c.origin * Eigen::Vector3d(0, 0, 0.25), Eigen::Vector3d(0, 0, 1.25)));

  Planned urdf(capsule, urdf_like());
  CHECK(urdf.plan.losses.empty());
  CHECK(urdf.only_piece().kind == Kind::kMesh);
  CHECK_FALSE(urdf.only_piece().mesh->empty());
  // A mesh keeps the shape's own rotation: the tessellated capsule runs along its +Y.
  CHECK(near(urdf.only_piece().origin.linear() * Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()));
}

TEST_CASE("shape plan: other geometry is tessellated in every target without a loss") {
  for (const ShapeTarget& target : {urdf_like(), mjcf_like()}) {
    Planned cone("      - {type: Shape, geometry: {type: Cone, radius: 0.1, height: 0.4}}\n", target);
    CHECK(cone.plan.losses.empty());
    CHECK(cone.only_piece().kind == Kind::kMesh);
    CHECK(cone.only_piece().stem == "L_shape0");
  }
}

TEST_CASE("shape plan: appearance losses follow the target: textures everywhere, emission where it has none") {
  const std::string shape = R"(      - type: Shape
        geometry: {type: Box, size: [1, 1, 1]}
        appearance:
          material: {diffuse: [1, 0, 0], emissive: [0, 1, 0]}
          texture: {uri: "missing.png"}
)";
  Planned urdf(shape, urdf_like());
  INFO(urdf.losses());
  REQUIRE(urdf.plan.losses.size() == 2);
  CHECK(urdf.plan.losses[0].kind == LossKind::kTextures);
  CHECK(urdf.plan.losses[1].kind == LossKind::kMaterials);
  CHECK(urdf.plan.losses[1].hint == "URDF materials have one rgba colour");
  check_at_shape(urdf.plan.losses[0]);
  // The emissive colour is named at its own key (line 12: the shape's 4th line), not at the
  // shape (issue 47).
  CHECK(urdf.plan.losses[1].at.line == 12);
  CHECK(urdf.plan.losses[1].at.column == int(std::string("          material: {diffuse: [1, 0, 0], ").size()) + 1);
  REQUIRE(urdf.only_piece().material.has_value());
  CHECK(urdf.only_piece().material->diffuse_color.x() == 1.0);

  Planned mjcf(shape, mjcf_like());
  REQUIRE(mjcf.plan.losses.size() == 1);
  CHECK(mjcf.plan.losses[0].kind == LossKind::kTextures);
}

TEST_CASE("shape plan: a lost emissive colour is named at its key, in the legacy spelling too") {
  const std::string shape = R"(      - type: Shape
        geometry: {type: Box, size: [1, 1, 1]}
        appearance:
          material:
            diffuseColor: [1, 0, 0]
            emissiveColor: [0, 1, 0]
)";
  Planned urdf(shape, urdf_like());
  INFO(urdf.losses());
  REQUIRE(urdf.plan.losses.size() == 1);
  CHECK(urdf.plan.losses[0].kind == LossKind::kMaterials);
  CHECK(urdf.plan.losses[0].at.line == 14);  // the shape's 6th line
  CHECK(urdf.plan.losses[0].at.column == 13);
}

TEST_CASE("shape plan: a shape that is neither visual nor collision has no pieces, and its losses stay") {
  for (const ShapeTarget& target : {urdf_like(), mjcf_like()}) {
    test::LoadResult loaded = test::load_v2(R"(
name: T
links:
  - name: L
    joint_type: free
    mass: 1
    elements:
      - type: Shape
        geometry: {type: Box, size: [1, 1, 1]}
        appearance: {texture: {uri: "missing.png"}}
)");
    Model model = loaded.m();
    model.links[0].shapes[0].visual = false;
    model.links[0].shapes[0].collision = false;
    CollectingSink sink;
    const ShapePlan plan = plan_shape(model, 0, 0, target, sink);
    CHECK(plan.pieces.empty());
    REQUIRE(plan.losses.size() == 1);
    CHECK(plan.losses[0].kind == LossKind::kTextures);
    check_at_shape(plan.losses[0]);
  }
}

TEST_CASE("shape plan: a mesh file is referenced as it is where the target can, its parts converted where not") {
  const std::string mesh = fmt::format(R"(      - type: Shape
        translation: [0, 0, 1]
        geometry: {{type: Resource, uri: "{}/square.obj"}}
)",
                                       kMeshDir);
  Planned urdf(mesh, urdf_like());
  CHECK(urdf.plan.losses.empty());
  const PlannedPiece& file = urdf.only_piece();
  CHECK(file.kind == Kind::kMeshFile);
  REQUIRE(file.file != nullptr);
  CHECK(file.file->uri.find("square.obj") != std::string::npos);
  CHECK(near(file.origin.translation(), Eigen::Vector3d(0, 0, 1)));

  // The square is flat: MuJoCo cannot hull it, so its collision geometry is dropped.
  Planned mjcf(mesh, mjcf_like());
  CHECK(mjcf.plan.losses.empty());
  const PlannedPiece& part = mjcf.only_piece();
  CHECK(part.kind == Kind::kMesh);
  CHECK(part.key == "asset:0:0");
  CHECK(part.stem == "square");
  REQUIRE(part.material.has_value());  // the part's own (red) material: the shape has none
  CHECK(part.material->diffuse_color.x() == doctest::Approx(1.0));
  REQUIRE(part.collision_dropped.has_value());
  CHECK(part.collision_dropped->kind == LossKind::kGeometry);
  check_at_shape(*part.collision_dropped);

  // A material the shape gives wins over the part's own.
  Planned blue(fmt::format(R"(      - type: Shape
        geometry: {{type: Resource, uri: "{}/square.obj"}}
        appearance: {{material: {{diffuse: [0, 0, 1]}}}}
)",
                           kMeshDir),
               mjcf_like());
  REQUIRE(blue.only_piece().material.has_value());
  CHECK(blue.only_piece().material->diffuse_color.x() == 0.0);
  CHECK(blue.only_piece().material->diffuse_color.z() == 1.0);
}

TEST_CASE("shape plan: a target that collides with hulls keeps a mesh with a volume, and a visual-only flat one") {
  Planned solid("      - {type: Shape, geometry: {type: Cone, radius: 0.1, height: 0.4}}\n", mjcf_like());
  CHECK_FALSE(solid.only_piece().collision_dropped.has_value());
  Planned visual(fmt::format(R"(      - type: Visual
        elements:
          - {{type: Shape, geometry: {{type: Resource, uri: "{}/square.obj"}}}}
)",
                             kMeshDir),
                 mjcf_like());
  REQUIRE(!visual.shape().collision);
  CHECK_FALSE(visual.only_piece().collision_dropped.has_value());
}

TEST_CASE("shape plan: a mesh that could not be loaded is left out and reported") {
  for (const ShapeTarget& target : {urdf_like(), mjcf_like()}) {
    test::LoadResult loaded = test::load_v2(R"(
name: T
links:
  - name: L
    joint_type: free
    mass: 1
    elements:
      - {type: Shape, geometry: {type: Resource, uri: "no_such_file.stl"}}
)");
    const Model& model = loaded.m();
    CollectingSink sink;
    const ShapePlan plan = plan_shape(model, 0, 0, target, sink);
    CHECK(plan.pieces.empty());
    REQUIRE(plan.losses.size() == 1);
    CHECK(plan.losses[0].kind == LossKind::kGeometry);
    CHECK(plan.losses[0].what.find("could not be loaded") != std::string::npos);
    check_at_shape(plan.losses[0]);
  }
}
