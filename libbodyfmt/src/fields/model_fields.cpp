#include "fields/model_fields.h"

#include <bodyfmt/read_file.h>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <type_traits>

namespace bodyfmt::detail {
namespace {

using S = FieldStyle;
using U = FieldUnit;
constexpr FieldComparison kExact = FieldComparison::kExact;
constexpr FieldComparison kTolerance = FieldComparison::kTolerance;

void set_vector(Field& f, const Eigen::Vector3d& v) { f.numbers = {v.x(), v.y(), v.z()}; }

// Translation (3) then the 3x3 part, row-major.
template <typename Transform>
void set_transform(Field& f, const Transform& X) {
  const Eigen::Matrix<double, 3, 4> M = X.matrix().template topRows<3>();
  f.numbers = {M(0, 3), M(1, 3), M(2, 3)};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) f.numbers.push_back(M(r, c));
}

// Column-major, as Eigen stores it (the tensors compared are symmetric).
void set_matrix(Field& f, const Eigen::Matrix3d& m) { f.numbers.assign(m.data(), m.data() + 9); }

void set_box(Field& f, const BoundingBox& b) {
  f.numbers = {b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z()};
}

std::string link_name(const Model& model, LinkIndex i) { return i >= 0 ? model.links[i].name : std::string(); }

bool movable(const LinkSubject& s) {
  return s.link.joint_type != JointType::kFixed && s.link.joint_type != JointType::kFree;
}

// ---------------------------------------------------------------------------------------------
// The whole model and its extra joints.

const FieldTable<ModelSubject> kModelFields = {
    {{"name", S::kText, U::kText, kExact},
     nullptr,
     [](const ModelSubject& s, Field& f) { f.text = s.model.name, f.source = s.model.source; }},
    {{"total_mass", S::kNumber, U::kMass, kTolerance, true},
     [](const ModelSubject& s) { return s.derived != nullptr; },
     [](const ModelSubject& s, Field& f) { f.numbers = {s.derived->total_mass}, f.source = s.model.source; }},
    {{"center_of_mass", S::kVector, U::kLength, kTolerance, true},
     [](const ModelSubject& s) { return s.derived != nullptr; },
     [](const ModelSubject& s, Field& f) {
       const Derived& d = *s.derived;
       Eigen::Vector3d moment = Eigen::Vector3d::Zero();
       for (std::size_t i = 0; i < s.model.links.size(); ++i)
         moment += d.mass[i].mass * (as_isometry(d.X_WL[i]) * d.mass[i].center_of_mass);
       set_vector(f, d.total_mass != 0 ? Eigen::Vector3d(moment / d.total_mass) : moment);
       f.source = s.model.source;
     }},
};

const FieldTable<ExtraJointSubject> kExtraJointFields = {
    {{"", S::kText, U::kText, kExact},
     nullptr,
     [](const ExtraJointSubject& s, Field& f) {
       f.text = fmt::format("{} '{}' '{}'", s.joint.type, link_name(s.model, s.joint.link1),
                            link_name(s.model, s.joint.link2));
       f.source = s.joint.source;
     }},
    {{"axis", S::kVector, U::kDirection},
     nullptr,
     [](const ExtraJointSubject& s, Field& f) { set_vector(f, s.joint.axis), f.source = s.joint.source; }},
    {{"link1 frame", S::kPose, U::kPose},
     nullptr,
     [](const ExtraJointSubject& s, Field& f) { set_transform(f, s.joint.X_1J), f.source = s.joint.source; }},
    {{"link2 frame", S::kPose, U::kPose},
     nullptr,
     [](const ExtraJointSubject& s, Field& f) { set_transform(f, s.joint.X_2J), f.source = s.joint.source; }},
};

// ---------------------------------------------------------------------------------------------
// A link: its joint, its place in the tree and its mass data (combined, as every tool reads it).

const FieldTable<LinkSubject> kLinkFields = {
    {{"parent", S::kText, U::kText, kExact},
     nullptr,
     [](const LinkSubject& s, Field& f) {
       f.text = link_name(s.model, s.link.parent), f.source = source_of(s.link, LinkSources::kParent);
     }},
    {{"joint_name", S::kText, U::kText, kExact},
     [](const LinkSubject& s) { return !s.link.joint_name.empty(); },
     [](const LinkSubject& s, Field& f) { f.text = s.link.joint_name, f.source = s.link.source; }},
    {{"translation", S::kVector, U::kLength},
     nullptr,
     [](const LinkSubject& s, Field& f) {
       set_vector(f, s.link.X_PL.translation()), f.source = source_of(s.link, LinkSources::kTranslation);
     }},
    {{"rotation", S::kRotation, U::kRotation},
     nullptr,
     [](const LinkSubject& s, Field& f) {
       const Eigen::Matrix3d R = s.link.X_PL.linear();
       f.numbers = {0, 0, 0};
       for (int r = 0; r < 3; ++r)
         for (int c = 0; c < 3; ++c) f.numbers.push_back(R(r, c));
       f.source = source_of(s.link, LinkSources::kRotation);
     }},
    {{"joint_type", S::kText, U::kEnum, kExact},
     nullptr,
     [](const LinkSubject& s, Field& f) {
       f.text = std::string(joint_type_name(s.link.joint_type)), f.source = source_of(s.link, LinkSources::kJointType);
     }},
    {{"joint_axis", S::kVector, U::kDirection},
     movable,
     [](const LinkSubject& s, Field& f) {
       set_vector(f, s.link.joint_axis), f.source = source_of(s.link, LinkSources::kJointAxis);
     }},
    {{"joint_range", S::kRange, U::kJointPosition},
     movable,
     [](const LinkSubject& s, Field& f) {
       f.numbers = {s.link.joint_range_lower, s.link.joint_range_upper};
       if (s.link.joint_type == JointType::kRevolute) f.style = S::kAngleRange;
       f.source = source_of(s.link, LinkSources::kJointRange);
     }},
    {{"joint_velocity_range", S::kRange, U::kJointVelocity},
     movable,
     [](const LinkSubject& s, Field& f) {
       f.numbers = {s.link.velocity_lower, s.link.velocity_upper};
       f.source = source_of(s.link, LinkSources::kJointVelocity);
     }},
    {{"joint_effort_range", S::kRange, U::kJointEffort},
     movable,
     [](const LinkSubject& s, Field& f) {
       f.numbers = {s.link.effort_lower, s.link.effort_upper}, f.source = s.link.source;
     }},
    {{"joint_axis_inertia", S::kNumber, U::kRotorInertia},
     movable,
     [](const LinkSubject& s, Field& f) { f.numbers = {s.link.joint_axis_inertia}, f.source = s.link.source; }},
    {{"initial_displacement", S::kNumber, U::kJointPosition},
     movable,
     [](const LinkSubject& s, Field& f) { f.numbers = {s.link.initial_displacement}, f.source = s.link.source; }},
    {{"joint_id", S::kNumber, U::kInteger, kExact},
     nullptr,
     [](const LinkSubject& s, Field& f) {
       f.numbers = {double(s.link.joint_id)}, f.source = source_of(s.link, LinkSources::kJointId);
     }},
    {{"actuation_mode", S::kText, U::kEnum, kExact},
     [](const LinkSubject& s) { return !s.link.actuation_mode.empty(); },
     [](const LinkSubject& s, Field& f) { f.text = s.link.actuation_mode, f.source = s.link.source; }},
    {{"material", S::kText, U::kText, kExact},
     [](const LinkSubject& s) { return !s.link.contact_material.empty(); },
     [](const LinkSubject& s, Field& f) { f.text = s.link.contact_material, f.source = s.link.source; }},
    {{"mass", S::kNumber, U::kMass},
     nullptr,
     [](const LinkSubject& s, Field& f) {
       f.numbers = {s.mass.mass};
       f.source = first_known({s.link.sources.mass(), rigid_body_source(s.link), s.link.source});
     }},
    {{"center_of_mass", S::kVector, U::kLength},
     nullptr,
     [](const LinkSubject& s, Field& f) {
       set_vector(f, s.mass.center_of_mass);
       f.source = first_known({s.link.sources.center_of_mass(), rigid_body_source(s.link), s.link.source});
     }},
    {{"inertia", S::kInertia, U::kInertia},
     nullptr,
     [](const LinkSubject& s, Field& f) { set_matrix(f, s.mass.inertia), f.source = inertia_source(s.link); }},
};

// ---------------------------------------------------------------------------------------------
// A shape: its geometry (the rows present depend on the geometry's type), placement and look.

template <typename... T>
bool shape_is(const ShapeSubject& s) {
  return (geometry_is<T>(s.shape.geometry) || ...);
}

const MeshResource& mesh_of(const ShapeSubject& s) { return geometry_get<MeshResource>(s.shape.geometry); }

// Extrusion, ElevationGrid, IndexedFaceSet, TriangleMesh: every number of the geometry.
void read_geometry_data(const ShapeSubject& s, Field& f) {
  std::vector<double>& n = f.numbers;
  std::visit(
      [&](const auto& stored) {
        const auto& g = geometry_value(stored);
        using T = std::decay_t<decltype(g)>;
        auto add2 = [&](const std::vector<Eigen::Vector2d>& v) {
          for (const auto& p : v) n.insert(n.end(), {p.x(), p.y()});
        };
        auto add3 = [&](const std::vector<Eigen::Vector3d>& v) {
          for (const auto& p : v) n.insert(n.end(), {p.x(), p.y(), p.z()});
        };
        auto addi = [&](const std::vector<int>& v) { n.insert(n.end(), v.begin(), v.end()); };
        if constexpr (std::is_same_v<T, Extrusion>) {
          add2(g.cross_section);
          add3(g.spine);
          for (const auto& o : g.orientation) n.insert(n.end(), {o.angle(), o.axis().x(), o.axis().y(), o.axis().z()});
          add2(g.scale);
          n.insert(n.end(), {g.crease_angle, double(g.begin_cap), double(g.end_cap)});
        } else if constexpr (std::is_same_v<T, ElevationGrid>) {
          n.insert(n.end(), {double(g.x_dimension), double(g.z_dimension), g.x_spacing, g.z_spacing});
          n.insert(n.end(), g.height.begin(), g.height.end());
          n.insert(n.end(), {double(g.ccw), g.crease_angle});
        } else if constexpr (std::is_same_v<T, IndexedFaceSet> || std::is_same_v<T, TriangleMeshGeometry>) {
          add3(g.vertices);
          addi(g.faces);
          add2(g.tex_coords);
          addi(g.tex_coord_indices);
          n.push_back(g.crease_angle);
        }
      },
      s.shape.geometry);
  f.text = fmt::format("{} numbers", n.size());
  f.source = s.shape.source;
}

template <typename T>
double radius_of(const ShapeSubject& s) {
  return geometry_get<T>(s.shape.geometry).radius;
}
double shape_radius(const ShapeSubject& s) {
  const Geometry& g = s.shape.geometry;
  if (geometry_is<Sphere>(g)) return radius_of<Sphere>(s);
  if (geometry_is<Cylinder>(g)) return radius_of<Cylinder>(s);
  if (geometry_is<Cone>(g)) return radius_of<Cone>(s);
  return radius_of<Capsule>(s);
}
double shape_height(const ShapeSubject& s) {
  const Geometry& g = s.shape.geometry;
  if (geometry_is<Cylinder>(g)) return geometry_get<Cylinder>(g).height;
  if (geometry_is<Cone>(g)) return geometry_get<Cone>(g).height;
  return geometry_get<Capsule>(g).height;
}

const Material& material_of(const ShapeSubject& s) { return *s.shape.appearance.material; }
bool has_material(const ShapeSubject& s) { return s.shape.appearance.material.has_value(); }

const FieldTable<ShapeSubject> kShapeFields = {
    {{"geometry", S::kText, U::kEnum, kExact},
     nullptr,
     [](const ShapeSubject& s, Field& f) {
       f.text = std::string(geometry_type_name(s.shape.geometry)), f.source = s.shape.source;
     }},
    {{"size", S::kVector, U::kLength, kTolerance, false, true},
     shape_is<Box>,
     [](const ShapeSubject& s, Field& f) {
       set_vector(f, geometry_get<Box>(s.shape.geometry).size), f.source = s.shape.source;
     }},
    {{"radius", S::kNumber, U::kLength, kTolerance, false, true},
     shape_is<Sphere, Cylinder, Cone, Capsule>,
     [](const ShapeSubject& s, Field& f) { f.numbers = {shape_radius(s)}, f.source = s.shape.source; }},
    {{"height", S::kNumber, U::kLength, kTolerance, false, true},
     shape_is<Cylinder, Cone, Capsule>,
     [](const ShapeSubject& s, Field& f) { f.numbers = {shape_height(s)}, f.source = s.shape.source; }},
    {{"caps", S::kText, U::kEnum, kExact, false, true},
     shape_is<Cylinder, Cone>,
     [](const ShapeSubject& s, Field& f) {
       const Geometry& g = s.shape.geometry;
       f.text = geometry_is<Cylinder>(g)
                    ? fmt::format("top {} bottom {}", geometry_get<Cylinder>(g).top, geometry_get<Cylinder>(g).bottom)
                    : fmt::format("bottom {}", geometry_get<Cone>(g).bottom);
       f.source = s.shape.source;
     }},
    {{"mesh", S::kText, U::kFile, kExact, false, true},
     shape_is<MeshResource>,
     [](const ShapeSubject& s, Field& f) {
       const MeshResource& m = mesh_of(s);
       f.text = m.uri;
       f.compare_text = s.files.key(m.uri, m.resolved_path);
       f.source = m.uri_source.known() ? m.uri_source : s.shape.source;
     }},
    {{"mesh node", S::kText, U::kText, kExact, false, true},
     [](const ShapeSubject& s) { return shape_is<MeshResource>(s) && !mesh_of(s).node.empty(); },
     [](const ShapeSubject& s, Field& f) { f.text = mesh_of(s).node, f.source = s.shape.source; }},
    {{"mesh length_scale", S::kNumber, U::kDimensionless, kTolerance, false, true},
     shape_is<MeshResource>,
     [](const ShapeSubject& s, Field& f) { f.numbers = {mesh_of(s).length_scale}, f.source = s.shape.source; }},
    {{"mesh upper_axis", S::kText, U::kEnum, kExact, false, true},
     shape_is<MeshResource>,
     [](const ShapeSubject& s, Field& f) { f.text = mesh_of(s).y_up ? "Y" : "Z", f.source = s.shape.source; }},
    {{"crease_angle", S::kNumber, U::kAngle, kTolerance, false, true},
     [](const ShapeSubject& s) { return shape_is<MeshResource>(s) && mesh_of(s).crease_angle.has_value(); },
     [](const ShapeSubject& s, Field& f) { f.numbers = {*mesh_of(s).crease_angle}, f.source = s.shape.source; }},
    {{"geometry data", S::kNumber, U::kGeometryData, kTolerance, false, true},
     shape_is<Extrusion, ElevationGrid, IndexedFaceSet, TriangleMeshGeometry>,
     read_geometry_data},
    {{"placement", S::kAffine, U::kPlacement},
     nullptr,
     [](const ShapeSubject& s, Field& f) { set_transform(f, s.shape.X_LS), f.source = s.shape.source; }},
    {{"role", S::kText, U::kEnum, kExact},
     nullptr,
     [](const ShapeSubject& s, Field& f) {
       const Shape& sh = s.shape;
       f.text = sh.visual && sh.collision ? "visual and collision"
                : sh.visual               ? "visual"
                : sh.collision            ? "collision"
                                          : "none";
       f.source = sh.source;
     }},
    {{"division_number", S::kNumber, U::kInteger, kExact},
     [](const ShapeSubject& s) { return s.shape.division_number != 20; },
     [](const ShapeSubject& s, Field& f) { f.numbers = {double(s.shape.division_number)}, f.source = s.shape.source; }},
    {{"material diffuse_color", S::kVector, U::kColor},
     has_material,
     [](const ShapeSubject& s, Field& f) { set_vector(f, material_of(s).diffuse_color), f.source = s.shape.source; }},
    {{"material specular_color", S::kVector, U::kColor},
     has_material,
     [](const ShapeSubject& s, Field& f) { set_vector(f, material_of(s).specular_color), f.source = s.shape.source; }},
    {{"material emissive_color", S::kVector, U::kColor},
     has_material,
     [](const ShapeSubject& s, Field& f) { set_vector(f, material_of(s).emissive_color), f.source = s.shape.source; }},
    {{"material ambient_intensity", S::kNumber, U::kDimensionless},
     has_material,
     [](const ShapeSubject& s, Field& f) {
       f.numbers = {material_of(s).ambient_intensity}, f.source = s.shape.source;
     }},
    {{"material specular_exponent", S::kNumber, U::kDimensionless},
     has_material,
     [](const ShapeSubject& s, Field& f) {
       f.numbers = {material_of(s).specular_exponent}, f.source = s.shape.source;
     }},
    {{"material transparency", S::kNumber, U::kDimensionless},
     has_material,
     [](const ShapeSubject& s, Field& f) { f.numbers = {material_of(s).transparency}, f.source = s.shape.source; }},
    {{"texture", S::kText, U::kFile, kExact},
     [](const ShapeSubject& s) { return s.shape.appearance.texture.has_value(); },
     [](const ShapeSubject& s, Field& f) {
       const Texture& t = *s.shape.appearance.texture;
       f.text = t.uri;
       f.compare_text = s.files.key(t.uri, t.resolved_path);
       f.source = s.shape.source;
     }},
};

// ---------------------------------------------------------------------------------------------
// A link's derived effects: its world frame at the zero pose and the boxes of its geometry.

const FieldTable<LinkDerivedSubject> kLinkDerivedFields = {
    {{"world_frame", S::kPose, U::kPose, kTolerance, true},
     nullptr,
     [](const LinkDerivedSubject& s, Field& f) { set_transform(f, s.X_WL), f.source = s.at; }},
    {{"visual_bounding_box", S::kBox, U::kLength, kTolerance, true},
     [](const LinkDerivedSubject& s) { return !s.bounds.visual.empty(); },
     [](const LinkDerivedSubject& s, Field& f) { set_box(f, s.bounds.visual), f.source = s.at; }},
    {{"collision_bounding_box", S::kBox, U::kLength, kTolerance, true},
     [](const LinkDerivedSubject& s) { return !s.bounds.collision.empty(); },
     [](const LinkDerivedSubject& s, Field& f) { set_box(f, s.bounds.collision), f.source = s.at; }},
};

// ---------------------------------------------------------------------------------------------
// A device: what every device has, then its parameters by kind (the rows of one kind present).

template <typename P>
bool params_are(const DeviceSubject& s) {
  return std::holds_alternative<P>(s.device.params);
}

// A parameter, located at its key.
template <typename P, typename T, T P::*member>
void param(const DeviceSubject& s, Field& f) {
  const T& v = std::get<P>(s.device.params).*member;
  if constexpr (std::is_same_v<T, std::string>)
    f.text = v;
  else if constexpr (std::is_same_v<T, Eigen::Vector3d>)
    set_vector(f, v);
  else
    f.numbers = {double(v)};
  f.source = s.device.key_source({f.traits->name});
}

template <typename P, typename T, T P::*member>
FieldSpec<DeviceSubject> row(std::string_view name, FieldStyle style, FieldUnit unit,
                             FieldComparison comparison = kTolerance) {
  return {{name, style, unit, comparison}, params_are<P>, param<P, T, member>};
}

using C = CameraParams;
using R = RangeSensorParams;
using L = LightParams;
using F = ForceSensorParams;
using I = InertialSensorParams;
using V = Eigen::Vector3d;

const FieldTable<DeviceSubject> kDeviceFields = {
    {{"type", S::kText, U::kText, kExact},
     nullptr,
     [](const DeviceSubject& s, Field& f) { f.text = s.device.type, f.source = s.device.source; }},
    {{"id", S::kNumber, U::kInteger, kExact},
     nullptr,
     [](const DeviceSubject& s, Field& f) {
       f.numbers = {double(s.device.id)}, f.source = s.device.key_source({"id"});
     }},
    {{"placement", S::kPose, U::kPose},
     nullptr,
     [](const DeviceSubject& s, Field& f) { set_transform(f, s.device.X_LD), f.source = s.device.source; }},
    {{"on", S::kText, U::kEnum, kExact},
     [](const DeviceSubject& s) { return !s.device.on; },
     [](const DeviceSubject& s, Field& f) { f.text = "false", f.source = s.device.key_source({"on"}); }},
    row<C, std::string, &C::format>("format", S::kText, U::kEnum, kExact),
    row<C, std::string, &C::lens_type>("lens_type", S::kText, U::kEnum, kExact),
    row<C, int, &C::width>("width", S::kNumber, U::kInteger, kExact),
    row<C, int, &C::height>("height", S::kNumber, U::kInteger, kExact),
    row<C, double, &C::field_of_view>("field_of_view", S::kNumber, U::kAngle),
    row<C, double, &C::near_clip_distance>("near_clip_distance", S::kNumber, U::kLength),
    row<C, double, &C::far_clip_distance>("far_clip_distance", S::kNumber, U::kLength),
    row<C, double, &C::frame_rate>("frame_rate", S::kNumber, U::kFrequency),
    row<C, std::string, &C::optical_frame>("optical_frame", S::kText, U::kEnum, kExact),
    {{"optical_frame_rotation", S::kNumber, U::kRotation},
     params_are<C>,
     [](const DeviceSubject& s, Field& f) {
       set_matrix(f, std::get<C>(s.device.params).optical_frame_rotation), f.source = s.device.source;
     }},
    row<C, double, &C::min_distance>("min_distance", S::kNumber, U::kLength),
    row<C, double, &C::max_distance>("max_distance", S::kNumber, U::kLength),
    row<C, double, &C::detection_rate>("detection_rate", S::kNumber, U::kDimensionless),
    row<C, double, &C::error_deviation>("error_deviation", S::kNumber, U::kLength),
    row<R, double, &R::yaw_range>("yaw_range", S::kNumber, U::kAngle),
    row<R, double, &R::yaw_step>("yaw_step", S::kNumber, U::kAngle),
    row<R, double, &R::pitch_range>("pitch_range", S::kNumber, U::kAngle),
    row<R, double, &R::pitch_step>("pitch_step", S::kNumber, U::kAngle),
    row<R, double, &R::min_distance>("min_distance", S::kNumber, U::kLength),
    row<R, double, &R::max_distance>("max_distance", S::kNumber, U::kLength),
    row<R, double, &R::scan_rate>("scan_rate", S::kNumber, U::kFrequency),
    row<R, double, &R::detection_rate>("detection_rate", S::kNumber, U::kDimensionless),
    row<R, double, &R::error_deviation>("error_deviation", S::kNumber, U::kLength),
    row<L, V, &L::color>("color", S::kVector, U::kColor),
    row<L, double, &L::intensity>("intensity", S::kNumber, U::kDimensionless),
    row<L, V, &L::attenuation>("attenuation", S::kVector, U::kDimensionless),
    row<L, V, &L::direction>("direction", S::kVector, U::kDirection),
    row<L, double, &L::beam_width>("beam_width", S::kNumber, U::kAngle),
    row<L, double, &L::cut_off_angle>("cut_off_angle", S::kNumber, U::kAngle),
    row<L, double, &L::cut_off_exponent>("cut_off_exponent", S::kNumber, U::kDimensionless),
    row<F, V, &F::max_force>("max_force", S::kVector, U::kForce),
    row<F, V, &F::max_torque>("max_torque", S::kVector, U::kTorque),
    row<I, V, &I::max_angular_velocity>("max_angular_velocity", S::kVector, U::kAngularVelocity),
    row<I, V, &I::max_acceleration>("max_acceleration", S::kVector, U::kAcceleration),
};

// A device key's value, already in the field (read_device_keys reads the keys).
void keep(const DeviceSubject&, Field&) {}

const FieldSpec<DeviceSubject> kDeviceKeyNumber = {{"", S::kNumber, U::kUnknown}, params_are<OpaqueParams>, keep};
const FieldSpec<DeviceSubject> kDeviceKeyText = {{"", S::kText, U::kText, kExact}, params_are<OpaqueParams>, keep};

// `nodeThickness` and `node_thickness` alike: the field's name must not change with a spelling.
std::string snake_case(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (std::isupper(static_cast<unsigned char>(c))) {
      if (!out.empty() && out.back() != '_') out += '_';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

const FieldTable<ModelSubject>& model_field_table() { return kModelFields; }
const FieldTable<ExtraJointSubject>& extra_joint_field_table() { return kExtraJointFields; }
const FieldTable<LinkSubject>& link_field_table() { return kLinkFields; }
const FieldTable<ShapeSubject>& shape_field_table() { return kShapeFields; }
const FieldTable<LinkDerivedSubject>& link_derived_field_table() { return kLinkDerivedFields; }
const FieldTable<DeviceSubject>& device_field_table() { return kDeviceFields; }
const FieldSpec<DeviceSubject>& device_key_number_spec() { return kDeviceKeyNumber; }
const FieldSpec<DeviceSubject>& device_key_text_spec() { return kDeviceKeyText; }

// Lists (a track's sprocketNames) are not kept by the loader.
void read_device_keys(const Device& d, const std::string& prefix, std::vector<Field>& out) {
  if (!std::holds_alternative<OpaqueParams>(d.params)) return;
  std::map<std::string, std::pair<std::string, SourceLocation>> keys;
  for (const auto& [name, value] : d.keys) {
    const std::string plain = snake_case(name);
    // Read already (type, name, id, on), or an angle that --upgrade rewrites in other units.
    if (plain == "type" || plain == "name" || plain == "id" || plain == "on" || plain == "emission_range") continue;
    keys[plain] = {value, d.key_source({name})};
  }
  for (const auto& [plain, value_at] : keys) {
    const auto& [value, at] = value_at;
    Field f;
    f.key = prefix + " " + plain;
    f.element = prefix;
    f.source = at;
    char* end = nullptr;
    const double x = value.empty() ? 0 : std::strtod(value.c_str(), &end);
    if (!value.empty() && end && *end == '\0' && std::isfinite(x)) {
      f.traits = &kDeviceKeyNumber.traits;
      f.numbers = {x};
    } else {
      f.traits = &kDeviceKeyText.traits;
      f.text = value;
    }
    f.style = f.traits->style;
    out.push_back(std::move(f));
  }
}

std::string FileKeys::key(const std::string& uri, const std::string& resolved_path) {
  if (by_ == By::kPath) return "uri " + uri + " path " + resolved_path;
  if (resolved_path.empty()) return "uri " + uri;
  auto it = cache_.find(resolved_path);
  if (it != cache_.end()) return it->second;
  std::string why, key;
  if (auto bytes = read_regular_file(resolved_path, std::uintmax_t(1) << 30, why))
    key = fmt::format("{} bytes, hash {:016x}", bytes->size(), std::hash<std::string>()(*bytes));
  else
    key = "unreadable: " + why;
  return cache_.emplace(resolved_path, key).first->second;
}

bool same_number(double a, double b, double tolerance) {
  if (a == b || (std::isnan(a) && std::isnan(b))) return true;
  if (!std::isfinite(a) || !std::isfinite(b)) return false;
  return std::abs(a - b) <= tolerance * std::max({1.0, std::abs(a), std::abs(b)});
}

bool same_value(const Field& a, const Field& b, double tolerance) {
  if (a.style != b.style) return false;
  const std::string& ta = a.compare_text.empty() ? a.text : a.compare_text;
  const std::string& tb = b.compare_text.empty() ? b.text : b.compare_text;
  if (ta != tb || a.numbers.size() != b.numbers.size()) return false;
  const double within = a.traits->comparison == FieldComparison::kExact ? 0.0 : tolerance;
  for (std::size_t i = 0; i < a.numbers.size(); ++i)
    if (!same_number(a.numbers[i], b.numbers[i], within)) return false;
  return true;
}

}  // namespace bodyfmt::detail
