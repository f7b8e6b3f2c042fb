// The field table (libbodyfmt/src/fields/model_fields.h) against a table of mutants written by
// hand: every row of the field table is changed by some mutant, each mutant is reported by
// bodydiff (diff_models) at its field and by bodycheck --fix's comparison (model_difference),
// and the same edit scaled below the tolerance is reported by neither. A row dropped from the
// field table leaves its mutant unreported; a row added without a mutant fails the coverage.
#include "fields/model_fields.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/fix.h>
#include <bodyfmt/load.h>
#include <bodyfmt/model_diff.h>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace bodyfmt;

// x moved by eps relative to its size (absolute below 1), as the tolerance is defined.
void nudge(double& x, double eps) { x += eps * std::max(1.0, std::abs(x)); }
void nudge(Eigen::Vector3d& v, double eps) { nudge(v.x(), eps); }

template <typename T>
T& geometry(Model& m, std::size_t shape) {
  return *geometry_if<T>(m.links[1].shapes[shape].geometry);
}

Shape shape_of(Geometry g) {
  Shape s;
  s.geometry = std::move(g);
  return s;
}

// A model with every field the table holds: a root and a revolute ARM carrying one shape of each
// geometry type (materials, a texture; the cone is the widest, so that it makes both boxes), one device of each kind of
// parameters, an extra joint.
Model every_field_model() {
  CollectingSink sink;
  LoadOptions options;
  options.load_meshes = false;
  auto loaded = load_body_string(
      "format: ChoreonoidBody\nformat_version: 2.0\nname: all\nlinks:\n"
      "  - name: BASE\n    joint_type: free\n    mass: 10\n    center_of_mass: [ 0.1, 0.2, 0.3 ]\n"
      "    inertia: [ 1, 0, 0, 0, 2, 0, 0, 0, 3 ]\n"
      "  - name: ARM\n    parent: BASE\n    translation: [ 0.2, 0.3, 0.5 ]\n    rotation: [ 1, 0, 0, 30 ]\n"
      "    joint_type: revolute\n    joint_id: 3\n    joint_axis: [ 0, 0.6, 0.8 ]\n"
      "    joint_range: [ -90, 45 ]\n    max_joint_velocity: 2\n    mass: 2.5\n"
      "    center_of_mass: [ 0.01, 0.02, 0.03 ]\n    inertia: [ 0.4, 0, 0, 0, 0.5, 0, 0, 0, 0.6 ]\n"
      "  - name: TIP\n    parent: ARM\n    joint_type: fixed\n",
      "all.body", options, sink);
  REQUIRE(loaded);
  Model m = std::move(*loaded);
  Link& arm = m.links[1];
  arm.joint_name = "arm_joint";
  arm.effort_lower = -30, arm.effort_upper = 40;
  arm.joint_axis_inertia = 0.25;
  arm.initial_displacement = 0.5;
  arm.actuation_mode = "joint_torque";
  arm.contact_material = "steel";

  arm.shapes.push_back(shape_of(Box{Eigen::Vector3d(0.1, 0.2, 0.3)}));  // 0
  arm.shapes.push_back(shape_of(Sphere{0.15}));                         // 1
  arm.shapes.push_back(shape_of(Cylinder{0.1, 0.4, true, false}));      // 2
  arm.shapes.push_back(shape_of(Cone{3.0, 0.3, true}));                 // 3
  arm.shapes.push_back(shape_of(Capsule{0.05, 0.25}));                  // 4
  Extrusion extrusion;
  extrusion.cross_section = {{0, 0}, {1, 0}, {0, 1}, {0, 0}};
  extrusion.spine = {{0, 0, 0}, {0, 0.5, 0}};
  extrusion.scale = {{1, 1}};
  arm.shapes.push_back(shape_of(HeapValue<Extrusion>(extrusion)));  // 5
  ElevationGrid grid;
  grid.x_dimension = 2, grid.z_dimension = 2, grid.x_spacing = 0.5, grid.z_spacing = 0.5;
  grid.height = {0, 0.1, 0.2, 0.3};
  arm.shapes.push_back(shape_of(HeapValue<ElevationGrid>(grid)));  // 6
  IndexedFaceSet faces;
  faces.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  faces.faces = {0, 1, 2, -1};
  arm.shapes.push_back(shape_of(HeapValue<IndexedFaceSet>(faces)));  // 7
  TriangleMeshGeometry triangles;
  triangles.vertices = {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  triangles.faces = {0, 1, 2};
  arm.shapes.push_back(shape_of(HeapValue<TriangleMeshGeometry>(triangles)));  // 8
  MeshResource mesh;
  mesh.uri = "arm.stl";
  mesh.node = "upper";
  mesh.length_scale = 0.001;
  mesh.crease_angle = 0.5;
  arm.shapes.push_back(shape_of(HeapValue<MeshResource>(mesh)));  // 9
  Shape& looks = arm.shapes[0];
  Material material;
  material.diffuse_color = {0.8, 0.2, 0.1};
  material.specular_color = {0.3, 0.3, 0.3};
  material.emissive_color = {0.1, 0, 0};
  material.ambient_intensity = 0.4;
  material.transparency = 0.25;
  looks.appearance.material = material;
  Texture texture;
  texture.uri = "skin.png";
  looks.appearance.texture = texture;
  looks.division_number = 12;
  looks.X_LS.translation() = Eigen::Vector3d(0.01, 0.02, 0.03);
  arm.shapes[1].visual = false;

  auto device = [&](const char* type, const char* name, DeviceParams params) {
    Device d;
    d.node_type = d.type = type;
    d.name = name;
    d.id = static_cast<int>(m.devices.size());
    d.link = 1;
    d.params = std::move(params);
    d.X_LD.translation() = Eigen::Vector3d(0.1, 0, 0.05);
    m.devices.push_back(std::move(d));
  };
  CameraParams camera;
  camera.format = "COLOR";
  device("Camera", "cam", camera);
  device("RangeSensor", "lidar", RangeSensorParams{});
  LightParams light;
  light.color = {1, 0.9, 0.8};
  light.attenuation = {1, 0.1, 0.01};
  light.direction = {0, 0, -1};
  device("SpotLight", "lamp", light);
  device("ForceSensor", "wrist", ForceSensorParams{Eigen::Vector3d(100, 100, 200), Eigen::Vector3d(10, 10, 5)});
  device("RateGyroSensor", "gyro", InertialSensorParams{Eigen::Vector3d(5, 5, 5), Eigen::Vector3d(9, 9, 20)});
  device("Holder", "holder", OpaqueParams{});
  m.devices.back().keys = {{"holdRange", "0.02"}, {"category", "grip"}};

  ExtraJoint loop;
  loop.type = "hinge";
  loop.link1 = 0, loop.link2 = 1;
  loop.axis = {0, 1, 0};
  loop.X_1J.translation() = Eigen::Vector3d(0, 0, 0.2);
  loop.X_2J.translation() = Eigen::Vector3d(0, 0, -0.1);
  m.extra_joints.push_back(loop);
  return m;
}

// One mutant: the table and row it changes, the change bodydiff must report (link "" for the
// whole model), and the edit, by `eps` relative where the field is a measure.
struct Mutant {
  std::string table;  // model, extra_joint, link, shape, link_derived, device
  std::string row;    // the row's name in its table
  std::string link;
  std::string key;
  std::function<void(Model&, double eps)> edit;
  bool exact = false;  // an id, a count or text: changed by any edit
};

const char* kDevice[] = {"cam", "lidar", "lamp", "wrist", "gyro", "holder"};
Device& dev(Model& m, int i) { return m.devices[i]; }
template <typename P>
P& params(Model& m, int i) {
  return std::get<P>(m.devices[i].params);
}

std::vector<Mutant> mutants() {
  std::vector<Mutant> out = {
      {"model", "name", "", "name", [](Model& m, double) { m.name = "other"; }, true},
      {"model", "total_mass", "", "total_mass",
       [](Model& m, double e) { nudge(m.links[0].mass_contributions[0].mass, e); }},
      {"model", "center_of_mass", "", "center_of_mass",
       [](Model& m, double e) { nudge(m.links[0].mass_contributions[0].center_of_mass, e); }},
      {"extra_joint", "", "", "extra_joint 0", [](Model& m, double) { m.extra_joints[0].type = "piston"; }, true},
      {"extra_joint", "axis", "", "extra_joint 0 axis",
       [](Model& m, double e) { nudge(m.extra_joints[0].axis.y(), e); }},
      {"extra_joint", "link1 frame", "", "extra_joint 0 link1 frame",
       [](Model& m, double e) { nudge(m.extra_joints[0].X_1J.translation().z(), e); }},
      {"extra_joint", "link2 frame", "", "extra_joint 0 link2 frame",
       [](Model& m, double e) { nudge(m.extra_joints[0].X_2J.translation().z(), e); }},
      {"link", "parent", "TIP", "parent", [](Model& m, double) { m.links[2].parent = 0; }, true},
      {"link", "joint_name", "ARM", "joint_name", [](Model& m, double) { m.links[1].joint_name = "elbow"; }, true},
      {"link", "translation", "ARM", "translation",
       [](Model& m, double e) { nudge(m.links[1].X_PL.translation().x(), e); }},
      {"link", "rotation", "ARM", "rotation",
       [](Model& m, double e) {
         m.links[1].X_PL.linear() = Eigen::AngleAxisd(kPi / 6 + e, Eigen::Vector3d::UnitX()).toRotationMatrix();
       }},
      {"link", "joint_type", "ARM", "joint_type",
       [](Model& m, double) { m.links[1].joint_type = JointType::kPrismatic; }, true},
      {"link", "joint_axis", "ARM", "joint_axis", [](Model& m, double e) { nudge(m.links[1].joint_axis.y(), e); }},
      {"link", "joint_range", "ARM", "joint_range", [](Model& m, double e) { nudge(m.links[1].joint_range_upper, e); }},
      {"link", "joint_velocity_range", "ARM", "joint_velocity_range",
       [](Model& m, double e) { nudge(m.links[1].velocity_upper, e); }},
      {"link", "joint_effort_range", "ARM", "joint_effort_range",
       [](Model& m, double e) { nudge(m.links[1].effort_lower, e); }},
      {"link", "joint_axis_inertia", "ARM", "joint_axis_inertia",
       [](Model& m, double e) { nudge(m.links[1].joint_axis_inertia, e); }},
      {"link", "initial_displacement", "ARM", "initial_displacement",
       [](Model& m, double e) { nudge(m.links[1].initial_displacement, e); }},
      {"link", "joint_id", "ARM", "joint_id", [](Model& m, double) { m.links[1].joint_id = 4; }, true},
      {"link", "actuation_mode", "ARM", "actuation_mode",
       [](Model& m, double) { m.links[1].actuation_mode = "joint_velocity"; }, true},
      {"link", "material", "ARM", "material", [](Model& m, double) { m.links[1].contact_material = "rubber"; }, true},
      {"link", "mass", "ARM", "mass", [](Model& m, double e) { nudge(m.links[1].mass_contributions[0].mass, e); }},
      {"link", "center_of_mass", "ARM", "center_of_mass",
       [](Model& m, double e) { nudge(m.links[1].mass_contributions[0].center_of_mass.z(), e); }},
      {"link", "inertia", "ARM", "inertia",
       [](Model& m, double e) { nudge(m.links[1].mass_contributions[0].inertia(2, 2), e); }},
      {"link_derived", "world_frame", "ARM", "world_frame",
       [](Model& m, double e) { nudge(m.links[1].X_PL.translation().y(), e); }},
      {"link_derived", "visual_bounding_box", "ARM", "visual_bounding_box",
       [](Model& m, double e) { nudge(geometry<Cone>(m, 3).radius, e * 100); }},
      {"link_derived", "collision_bounding_box", "ARM", "collision_bounding_box",
       [](Model& m, double e) { nudge(geometry<Cone>(m, 3).radius, e * 100); }},
      {"shape", "geometry", "ARM", "shape 1 geometry", [](Model& m, double) { m.links[1].shapes[1].geometry = Box{}; },
       true},
      {"shape", "size", "ARM", "shape 0 size", [](Model& m, double e) { nudge(geometry<Box>(m, 0).size.z(), e); }},
      {"shape", "radius", "ARM", "shape 1 radius", [](Model& m, double e) { nudge(geometry<Sphere>(m, 1).radius, e); }},
      {"shape", "radius", "ARM", "shape 2 radius",
       [](Model& m, double e) { nudge(geometry<Cylinder>(m, 2).radius, e); }},
      {"shape", "radius", "ARM", "shape 3 radius", [](Model& m, double e) { nudge(geometry<Cone>(m, 3).radius, e); }},
      {"shape", "radius", "ARM", "shape 4 radius",
       [](Model& m, double e) { nudge(geometry<Capsule>(m, 4).radius, e); }},
      {"shape", "height", "ARM", "shape 2 height",
       [](Model& m, double e) { nudge(geometry<Cylinder>(m, 2).height, e); }},
      {"shape", "height", "ARM", "shape 3 height", [](Model& m, double e) { nudge(geometry<Cone>(m, 3).height, e); }},
      {"shape", "height", "ARM", "shape 4 height",
       [](Model& m, double e) { nudge(geometry<Capsule>(m, 4).height, e); }},
      {"shape", "caps", "ARM", "shape 2 caps", [](Model& m, double) { geometry<Cylinder>(m, 2).bottom = true; }, true},
      {"shape", "caps", "ARM", "shape 3 caps", [](Model& m, double) { geometry<Cone>(m, 3).bottom = false; }, true},
      {"shape", "geometry data", "ARM", "shape 5 geometry data",
       [](Model& m, double e) { nudge(geometry<Extrusion>(m, 5).spine[1].y(), e); }},
      {"shape", "geometry data", "ARM", "shape 6 geometry data",
       [](Model& m, double e) { nudge(geometry<ElevationGrid>(m, 6).height[3], e); }},
      {"shape", "geometry data", "ARM", "shape 7 geometry data",
       [](Model& m, double e) { nudge(geometry<IndexedFaceSet>(m, 7).vertices[1].x(), e); }},
      {"shape", "geometry data", "ARM", "shape 8 geometry data",
       [](Model& m, double e) { nudge(geometry<TriangleMeshGeometry>(m, 8).vertices[2].z(), e); }},
      {"shape", "mesh", "ARM", "shape 9 mesh", [](Model& m, double) { geometry<MeshResource>(m, 9).uri = "b.stl"; },
       true},
      {"shape", "mesh node", "ARM", "shape 9 mesh node",
       [](Model& m, double) { geometry<MeshResource>(m, 9).node = "lower"; }, true},
      {"shape", "mesh length_scale", "ARM", "shape 9 mesh length_scale",
       [](Model& m, double e) { nudge(geometry<MeshResource>(m, 9).length_scale, e); }},
      {"shape", "mesh upper_axis", "ARM", "shape 9 mesh upper_axis",
       [](Model& m, double) { geometry<MeshResource>(m, 9).y_up = true; }, true},
      {"shape", "crease_angle", "ARM", "shape 9 crease_angle",
       [](Model& m, double e) { nudge(*geometry<MeshResource>(m, 9).crease_angle, e); }},
      {"shape", "placement", "ARM", "shape 0 placement",
       [](Model& m, double e) { nudge(m.links[1].shapes[0].X_LS.translation().y(), e); }},
      {"shape", "role", "ARM", "shape 1 role", [](Model& m, double) { m.links[1].shapes[1].collision = false; }, true},
      {"shape", "division_number", "ARM", "shape 0 division_number",
       [](Model& m, double) { m.links[1].shapes[0].division_number = 16; }, true},
      {"shape", "material diffuse_color", "ARM", "shape 0 material diffuse_color",
       [](Model& m, double e) { nudge(m.links[1].shapes[0].appearance.material->diffuse_color, e); }},
      {"shape", "material specular_color", "ARM", "shape 0 material specular_color",
       [](Model& m, double e) { nudge(m.links[1].shapes[0].appearance.material->specular_color, e); }},
      {"shape", "material emissive_color", "ARM", "shape 0 material emissive_color",
       [](Model& m, double e) { nudge(m.links[1].shapes[0].appearance.material->emissive_color, e); }},
      {"shape", "material ambient_intensity", "ARM", "shape 0 material ambient_intensity",
       [](Model& m, double e) { nudge(m.links[1].shapes[0].appearance.material->ambient_intensity, e); }},
      {"shape", "material specular_exponent", "ARM", "shape 0 material specular_exponent",
       [](Model& m, double e) { nudge(m.links[1].shapes[0].appearance.material->specular_exponent, e); }},
      {"shape", "material transparency", "ARM", "shape 0 material transparency",
       [](Model& m, double e) { nudge(m.links[1].shapes[0].appearance.material->transparency, e); }},
      {"shape", "texture", "ARM", "shape 0 texture",
       [](Model& m, double) { m.links[1].shapes[0].appearance.texture->uri = "other.png"; }, true},
      {"device", "type", "ARM", "device 'holder' type", [](Model& m, double) { dev(m, 5).type = "ConveyorDevice"; },
       true},
      {"device", "id", "ARM", "device 'cam' id", [](Model& m, double) { dev(m, 0).id = 7; }, true},
      {"device", "placement", "ARM", "device 'gyro' placement",
       [](Model& m, double e) { nudge(dev(m, 4).X_LD.translation().z(), e); }},
      {"device", "on", "ARM", "device 'lamp' on", [](Model& m, double) { dev(m, 2).on = false; }, true},
  };
  auto add = [&](int device, const char* row, std::function<void(Model&, double)> edit, bool exact = false) {
    out.push_back(
        {"device", row, "ARM", std::string("device '") + kDevice[device] + "' " + row, std::move(edit), exact});
  };
  add(
      0, "format", [](Model& m, double) { params<CameraParams>(m, 0).format = "DEPTH"; }, true);
  add(
      0, "lens_type", [](Model& m, double) { params<CameraParams>(m, 0).lens_type = "FISHEYE"; }, true);
  add(
      0, "width", [](Model& m, double) { params<CameraParams>(m, 0).width = 641; }, true);
  add(
      0, "height", [](Model& m, double) { params<CameraParams>(m, 0).height = 481; }, true);
  add(0, "field_of_view", [](Model& m, double e) { nudge(params<CameraParams>(m, 0).field_of_view, e); });
  add(0, "near_clip_distance", [](Model& m, double e) { nudge(params<CameraParams>(m, 0).near_clip_distance, e); });
  add(0, "far_clip_distance", [](Model& m, double e) { nudge(params<CameraParams>(m, 0).far_clip_distance, e); });
  add(0, "frame_rate", [](Model& m, double e) { nudge(params<CameraParams>(m, 0).frame_rate, e); });
  add(
      0, "optical_frame", [](Model& m, double) { params<CameraParams>(m, 0).optical_frame = "cv"; }, true);
  add(0, "optical_frame_rotation",
      [](Model& m, double e) { nudge(params<CameraParams>(m, 0).optical_frame_rotation(1, 1), e); });
  add(0, "min_distance", [](Model& m, double e) { nudge(params<CameraParams>(m, 0).min_distance, e); });
  add(0, "max_distance", [](Model& m, double e) { nudge(params<CameraParams>(m, 0).max_distance, e); });
  add(0, "detection_rate", [](Model& m, double e) { nudge(params<CameraParams>(m, 0).detection_rate, e); });
  add(0, "error_deviation", [](Model& m, double e) { nudge(params<CameraParams>(m, 0).error_deviation, e); });
  add(1, "yaw_range", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).yaw_range, e); });
  add(1, "yaw_step", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).yaw_step, e); });
  add(1, "pitch_range", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).pitch_range, e); });
  add(1, "pitch_step", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).pitch_step, e); });
  add(1, "min_distance", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).min_distance, e); });
  add(1, "max_distance", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).max_distance, e); });
  add(1, "scan_rate", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).scan_rate, e); });
  add(1, "detection_rate", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).detection_rate, e); });
  add(1, "error_deviation", [](Model& m, double e) { nudge(params<RangeSensorParams>(m, 1).error_deviation, e); });
  add(2, "color", [](Model& m, double e) { nudge(params<LightParams>(m, 2).color, e); });
  add(2, "intensity", [](Model& m, double e) { nudge(params<LightParams>(m, 2).intensity, e); });
  add(2, "attenuation", [](Model& m, double e) { nudge(params<LightParams>(m, 2).attenuation, e); });
  add(2, "direction", [](Model& m, double e) { nudge(params<LightParams>(m, 2).direction, e); });
  add(2, "beam_width", [](Model& m, double e) { nudge(params<LightParams>(m, 2).beam_width, e); });
  add(2, "cut_off_angle", [](Model& m, double e) { nudge(params<LightParams>(m, 2).cut_off_angle, e); });
  add(2, "cut_off_exponent", [](Model& m, double e) { nudge(params<LightParams>(m, 2).cut_off_exponent, e); });
  add(3, "max_force", [](Model& m, double e) { nudge(params<ForceSensorParams>(m, 3).max_force, e); });
  add(3, "max_torque", [](Model& m, double e) { nudge(params<ForceSensorParams>(m, 3).max_torque, e); });
  add(4, "max_angular_velocity",
      [](Model& m, double e) { nudge(params<InertialSensorParams>(m, 4).max_angular_velocity, e); });
  add(4, "max_acceleration", [](Model& m, double e) { nudge(params<InertialSensorParams>(m, 4).max_acceleration, e); });
  // The scalar keys of a device no stage interprets: the table's two key rows.
  out.push_back({"device_key", "number", "ARM", "device 'holder' hold_range", [](Model& m, double e) {
                   double x = 0.02;
                   nudge(x, e);
                   dev(m, 5).keys["holdRange"] = fmt::format("{}", x);
                 }});
  out.push_back({"device_key", "text", "ARM", "device 'holder' category",
                 [](Model& m, double) { dev(m, 5).keys["category"] = "tool"; }, true});
  return out;
}

bool reports(const std::vector<ModelChange>& changes, const std::string& link, const std::string& key) {
  return std::any_of(changes.begin(), changes.end(),
                     [&](const ModelChange& c) { return c.link == link && c.field == key; });
}

std::string listed(const std::vector<ModelChange>& changes) {
  std::string out;
  for (const ModelChange& c : changes) out += c.link + ": " + c.field + " " + c.old_value + " -> " + c.new_value + "\n";
  return out;
}

}  // namespace

TEST_CASE("model fields: every row of the field table has a mutant in this test") {
  std::set<std::pair<std::string, std::string>> rows;
  auto add = [&](const char* table, const auto& specs) {
    for (const auto& spec : specs) rows.emplace(table, std::string(spec.traits.name));
  };
  add("model", detail::model_field_table());
  add("extra_joint", detail::extra_joint_field_table());
  add("link", detail::link_field_table());
  add("shape", detail::shape_field_table());
  add("link_derived", detail::link_derived_field_table());
  add("device", detail::device_field_table());
  rows.emplace("device_key", "number");
  rows.emplace("device_key", "text");
  std::set<std::pair<std::string, std::string>> covered;
  for (const Mutant& m : mutants()) covered.emplace(m.table, m.row);
  for (const auto& row : rows) {
    CAPTURE(row.first);
    CAPTURE(row.second);
    CHECK(covered.count(row));
  }
  for (const auto& row : covered) {
    CAPTURE(row.first);
    CAPTURE(row.second);
    CHECK(rows.count(row));  // a mutant for a row the table no longer has
  }
}

TEST_CASE("model fields: each mutant is reported at its field by bodydiff and by --fix's comparison") {
  const Model base = every_field_model();
  REQUIRE_FALSE(model_difference(base, base));
  REQUIRE(diff_models(base, base).empty());
  for (const Mutant& mutant : mutants()) {
    CAPTURE(mutant.key);
    Model changed = base;
    mutant.edit(changed, 1e-3);
    const std::vector<ModelChange> changes = diff_models(base, changed);
    CAPTURE(listed(changes));
    CHECK(reports(changes, mutant.link, mutant.key));
    CHECK(model_difference(base, changed));
  }
}

TEST_CASE("model fields: each mutant scaled below the tolerance is reported by neither") {
  const Model base = every_field_model();
  ModelDiffOptions options;
  options.tolerance = 1e-9;
  for (const Mutant& mutant : mutants()) {
    if (mutant.exact) continue;
    CAPTURE(mutant.key);
    Model changed = base;
    mutant.edit(changed, 1e-12);
    const std::vector<ModelChange> changes = diff_models(base, changed, options);
    CAPTURE(listed(changes));
    CHECK(changes.empty());
    const std::optional<std::string> difference = model_difference(base, changed, 1e-9);
    CHECK_MESSAGE(!difference, difference.value_or(""));
    // and --fix's own tolerance (1e-12, relative) sees an edit ten times as large
    Model moved = base;
    mutant.edit(moved, 1e-11);
    CHECK(model_difference(base, moved));
  }
}

TEST_CASE("model fields: ids and counts compare exactly, whatever the tolerance") {
  const Model base = every_field_model();
  Model changed = base;
  changed.links[1].joint_id = 4;  // 3 -> 4: within a tolerance of 0.5 relative
  ModelDiffOptions loose;
  loose.tolerance = 0.5;
  CHECK(reports(diff_models(base, changed, loose), "ARM", "joint_id"));
  CHECK(model_difference(base, changed, 0.5));
  changed = base;
  nudge(changed.links[1].X_PL.translation().x(), 0.1);  // a measure within it is the same
  CHECK(diff_models(base, changed, loose).empty());
}

TEST_CASE("model fields: what the table leaves out, --fix's comparison still holds in place") {
  const Model base = every_field_model();
  const std::vector<std::pair<const char*, std::function<void(Model&)>>> edits = {
      // a fixed joint's axis: no field of bodydiff's, but the model's and bodyinfo's
      {"fixed joint axis",
       [](Model& m) {
         m.links[2].joint_axis = {1, 0, 0};
       }},
      {"fixed joint range", [](Model& m) { m.links[2].joint_range_upper = 1; }},
      {"shape name", [](Model& m) { m.links[1].shapes[2].name = "renamed"; }},
      {"shapes reordered", [](Model& m) { std::swap(m.links[1].shapes[1], m.links[1].shapes[2]); }},
      {"mass split", [](Model& m) { m.links[1].mass_contributions.push_back(MassContribution{}); }},
      {"texture repeat", [](Model& m) { m.links[1].shapes[0].appearance.texture->repeat_s = false; }},
      {"device plugin", [](Model& m) { m.devices[5].plugin = true; }},
      {"devices reordered", [](Model& m) { std::swap(m.devices[0], m.devices[1]); }},
      {"body handler", [](Model& m) { m.body_handlers.push_back("Handler.so"); }},
  };
  for (const auto& what_edit : edits) {
    // Not a structured binding: clang 14 cannot capture one in CAPTURE's lambda.
    const auto& what = what_edit.first;
    CAPTURE(what);
    Model changed = base;
    what_edit.second(changed);
    CHECK(model_difference(base, changed));
  }
}
