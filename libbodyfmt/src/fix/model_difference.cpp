// Compares two loaded models field by field: the proof that a fixed file describes the same
// model as the original (bodycheck --fix writes nothing otherwise).

#include <bodyfmt/fix.h>

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <map>

namespace bodyfmt {
namespace {

class Comparer {
 public:
  explicit Comparer(double tolerance) : tolerance_(tolerance) {}

  std::optional<std::string> difference;

  bool same(double a, double b) const {
    if (a == b || (std::isnan(a) && std::isnan(b))) return true;
    if (!std::isfinite(a) || !std::isfinite(b)) return false;
    return std::abs(a - b) <= tolerance_ * std::max({1.0, std::abs(a), std::abs(b)});
  }

  void number(const std::string& what, double a, double b) {
    if (!difference && !same(a, b)) difference = fmt::format("{}: {} != {}", what, a, b);
  }
  template <typename Derived>
  void numbers(const std::string& what, const Eigen::MatrixBase<Derived>& a, const Eigen::MatrixBase<Derived>& b) {
    for (Eigen::Index i = 0; i < a.size() && !difference; ++i)
      number(fmt::format("{}[{}]", what, i), a.reshaped()(i), b.reshaped()(i));
  }
  void affine(const std::string& what, const Eigen::Affine3d& a, const Eigen::Affine3d& b) {
    numbers(what, a.matrix(), b.matrix());
  }
  void isometry(const std::string& what, const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    numbers(what, a.matrix(), b.matrix());
  }
  template <typename T>
  void equal(const std::string& what, const T& a, const T& b) {
    if (!difference && !(a == b)) difference = what + " differs";
  }
  void text(const std::string& what, const std::string& a, const std::string& b) {
    if (!difference && a != b) difference = fmt::format("{}: \"{}\" != \"{}\"", what, a, b);
  }
  bool count(const std::string& what, std::size_t a, std::size_t b) {
    if (!difference && a != b) difference = fmt::format("{}: {} != {} entries", what, a, b);
    return !difference;
  }
  template <typename T, typename F>
  void list(const std::string& what, const std::vector<T>& a, const std::vector<T>& b, F each) {
    if (!count(what, a.size(), b.size())) return;
    for (std::size_t i = 0; i < a.size() && !difference; ++i) each(fmt::format("{}[{}]", what, i), a[i], b[i]);
  }

  void material(const std::string& what, const std::optional<Material>& a, const std::optional<Material>& b) {
    if (!difference && a.has_value() != b.has_value()) difference = what + ": present in one model only";
    if (!a || !b) return;
    number(what + ".ambient_intensity", a->ambient_intensity, b->ambient_intensity);
    numbers(what + ".diffuse_color", a->diffuse_color, b->diffuse_color);
    numbers(what + ".emissive_color", a->emissive_color, b->emissive_color);
    numbers(what + ".specular_color", a->specular_color, b->specular_color);
    number(what + ".specular_exponent", a->specular_exponent, b->specular_exponent);
    number(what + ".transparency", a->transparency, b->transparency);
  }
  void texture(const std::string& what, const std::optional<Texture>& a, const std::optional<Texture>& b) {
    if (!difference && a.has_value() != b.has_value()) difference = what + ": present in one model only";
    if (!a || !b) return;
    text(what + ".uri", a->uri, b->uri);
    text(what + ".resolved_path", a->resolved_path, b->resolved_path);
    equal(what + ".repeat_s", a->repeat_s, b->repeat_s);
    equal(what + ".repeat_t", a->repeat_t, b->repeat_t);
  }
  void vectors2(const std::string& what, const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
    list(what, a, b, [&](const std::string& w, const auto& x, const auto& y) { numbers(w, x, y); });
  }
  void vectors3(const std::string& what, const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
    list(what, a, b, [&](const std::string& w, const auto& x, const auto& y) { numbers(w, x, y); });
  }
  void doubles(const std::string& what, const std::vector<double>& a, const std::vector<double>& b) {
    list(what, a, b, [&](const std::string& w, double x, double y) { number(w, x, y); });
  }

  void geometry(const std::string& what, const Geometry& ga, const Geometry& gb) {
    if (ga.index() != gb.index()) {
      if (!difference) difference = fmt::format("{}: {} != {}", what, geometry_type_name(ga), geometry_type_name(gb));
      return;
    }
    std::visit(
        [&](const auto& stored) {
          const auto& a = geometry_value(stored);
          using T = std::decay_t<decltype(a)>;
          const T& b = geometry_get<T>(gb);
          if constexpr (std::is_same_v<T, Box>) {
            numbers(what + ".size", a.size, b.size);
          } else if constexpr (std::is_same_v<T, Sphere>) {
            number(what + ".radius", a.radius, b.radius);
          } else if constexpr (std::is_same_v<T, Cylinder>) {
            number(what + ".radius", a.radius, b.radius);
            number(what + ".height", a.height, b.height);
            equal(what + ".top", a.top, b.top);
            equal(what + ".bottom", a.bottom, b.bottom);
          } else if constexpr (std::is_same_v<T, Cone>) {
            number(what + ".radius", a.radius, b.radius);
            number(what + ".height", a.height, b.height);
            equal(what + ".bottom", a.bottom, b.bottom);
          } else if constexpr (std::is_same_v<T, Capsule>) {
            number(what + ".radius", a.radius, b.radius);
            number(what + ".height", a.height, b.height);
          } else if constexpr (std::is_same_v<T, Extrusion>) {
            vectors2(what + ".cross_section", a.cross_section, b.cross_section);
            vectors3(what + ".spine", a.spine, b.spine);
            list(what + ".orientation", a.orientation, b.orientation,
                 [&](const std::string& w, const Eigen::AngleAxisd& x, const Eigen::AngleAxisd& y) {
                   number(w + ".angle", x.angle(), y.angle());
                   numbers(w + ".axis", x.axis(), y.axis());
                 });
            vectors2(what + ".scale", a.scale, b.scale);
            number(what + ".crease_angle", a.crease_angle, b.crease_angle);
            equal(what + ".begin_cap", a.begin_cap, b.begin_cap);
            equal(what + ".end_cap", a.end_cap, b.end_cap);
          } else if constexpr (std::is_same_v<T, ElevationGrid>) {
            equal(what + ".x_dimension", a.x_dimension, b.x_dimension);
            equal(what + ".z_dimension", a.z_dimension, b.z_dimension);
            number(what + ".x_spacing", a.x_spacing, b.x_spacing);
            number(what + ".z_spacing", a.z_spacing, b.z_spacing);
            doubles(what + ".height", a.height, b.height);
            equal(what + ".ccw", a.ccw, b.ccw);
            number(what + ".crease_angle", a.crease_angle, b.crease_angle);
          } else if constexpr (std::is_same_v<T, IndexedFaceSet> || std::is_same_v<T, TriangleMeshGeometry>) {
            vectors3(what + ".vertices", a.vertices, b.vertices);
            equal(what + ".faces", a.faces, b.faces);
            vectors2(what + ".tex_coords", a.tex_coords, b.tex_coords);
            equal(what + ".tex_coord_indices", a.tex_coord_indices, b.tex_coord_indices);
            number(what + ".crease_angle", a.crease_angle, b.crease_angle);
          } else if constexpr (std::is_same_v<T, MeshResource>) {
            text(what + ".uri", a.uri, b.uri);
            text(what + ".resolved_path", a.resolved_path, b.resolved_path);
            text(what + ".node", a.node, b.node);
            number(what + ".length_scale", a.length_scale, b.length_scale);
            equal(what + ".y_up", a.y_up, b.y_up);
            if (!difference && a.crease_angle.has_value() != b.crease_angle.has_value())
              difference = what + ".crease_angle: given in one model only";
            if (a.crease_angle && b.crease_angle) number(what + ".crease_angle", *a.crease_angle, *b.crease_angle);
            equal(what + ".mesh", a.mesh, b.mesh);
          }
        },
        ga);
  }

  void shape(const std::string& what, const Shape& a, const Shape& b) {
    text(what + ".name", a.name, b.name);
    geometry(what + ".geometry", a.geometry, b.geometry);
    material(what + ".material", a.appearance.material, b.appearance.material);
    texture(what + ".texture", a.appearance.texture, b.appearance.texture);
    affine(what + ".X_LS", a.X_LS, b.X_LS);
    equal(what + ".frame", a.frame, b.frame);
    equal(what + ".division_number", a.division_number, b.division_number);
    equal(what + ".visual", a.visual, b.visual);
    equal(what + ".collision", a.collision, b.collision);
  }

  void link(const std::string& what, const Link& a, const Link& b) {
    text(what + ".joint_name", a.joint_name, b.joint_name);
    equal(what + ".parent", a.parent, b.parent);
    equal(what + ".children", a.children, b.children);
    affine(what + ".X_PL", a.X_PL, b.X_PL);
    if (!difference && a.joint_type != b.joint_type)
      difference =
          fmt::format("{}.joint_type: {} != {}", what, joint_type_name(a.joint_type), joint_type_name(b.joint_type));
    numbers(what + ".joint_axis", a.joint_axis, b.joint_axis);
    equal(what + ".joint_id", a.joint_id, b.joint_id);
    number(what + ".joint_range_lower", a.joint_range_lower, b.joint_range_lower);
    number(what + ".joint_range_upper", a.joint_range_upper, b.joint_range_upper);
    number(what + ".velocity_lower", a.velocity_lower, b.velocity_lower);
    number(what + ".velocity_upper", a.velocity_upper, b.velocity_upper);
    number(what + ".effort_lower", a.effort_lower, b.effort_lower);
    number(what + ".effort_upper", a.effort_upper, b.effort_upper);
    number(what + ".initial_displacement", a.initial_displacement, b.initial_displacement);
    number(what + ".joint_axis_inertia", a.joint_axis_inertia, b.joint_axis_inertia);
    text(what + ".actuation_mode", a.actuation_mode, b.actuation_mode);
    text(what + ".contact_material", a.contact_material, b.contact_material);
    list(what + ".mass", a.mass_contributions, b.mass_contributions,
         [&](const std::string& w, const MassContribution& x, const MassContribution& y) {
           number(w + ".mass", x.mass, y.mass);
           numbers(w + ".center_of_mass", x.center_of_mass, y.center_of_mass);
           numbers(w + ".inertia", x.inertia, y.inertia);
           equal(w + ".from_link_keys", x.from_link_keys, y.from_link_keys);
         });
    list(what + ".shapes", a.shapes, b.shapes,
         [&](const std::string& w, const Shape& x, const Shape& y) { shape(w, x, y); });
    list(what + ".frames", a.frames, b.frames, [&](const std::string& w, const SceneFrame& x, const SceneFrame& y) {
      equal(w + ".parent", x.parent, y.parent);
      affine(w + ".X_PF", x.X_PF, y.X_PF);
    });
  }

  void params(const std::string& what, const DeviceParams& pa, const DeviceParams& pb) {
    if (pa.index() != pb.index()) {
      if (!difference) difference = what + ": a different kind of device";
      return;
    }
    std::visit(
        [&](const auto& a) {
          using T = std::decay_t<decltype(a)>;
          const T& b = std::get<T>(pb);
          if constexpr (std::is_same_v<T, CameraParams>) {
            text(what + ".format", a.format, b.format);
            text(what + ".lens_type", a.lens_type, b.lens_type);
            equal(what + ".width", a.width, b.width);
            equal(what + ".height", a.height, b.height);
            number(what + ".field_of_view", a.field_of_view, b.field_of_view);
            number(what + ".near_clip_distance", a.near_clip_distance, b.near_clip_distance);
            number(what + ".far_clip_distance", a.far_clip_distance, b.far_clip_distance);
            number(what + ".frame_rate", a.frame_rate, b.frame_rate);
            text(what + ".optical_frame", a.optical_frame, b.optical_frame);
            numbers(what + ".optical_frame_rotation", a.optical_frame_rotation, b.optical_frame_rotation);
            number(what + ".min_distance", a.min_distance, b.min_distance);
            number(what + ".max_distance", a.max_distance, b.max_distance);
            number(what + ".detection_rate", a.detection_rate, b.detection_rate);
            number(what + ".error_deviation", a.error_deviation, b.error_deviation);
          } else if constexpr (std::is_same_v<T, RangeSensorParams>) {
            number(what + ".yaw_range", a.yaw_range, b.yaw_range);
            number(what + ".yaw_step", a.yaw_step, b.yaw_step);
            number(what + ".pitch_range", a.pitch_range, b.pitch_range);
            number(what + ".pitch_step", a.pitch_step, b.pitch_step);
            number(what + ".min_distance", a.min_distance, b.min_distance);
            number(what + ".max_distance", a.max_distance, b.max_distance);
            number(what + ".scan_rate", a.scan_rate, b.scan_rate);
            number(what + ".detection_rate", a.detection_rate, b.detection_rate);
            number(what + ".error_deviation", a.error_deviation, b.error_deviation);
          } else if constexpr (std::is_same_v<T, LightParams>) {
            numbers(what + ".color", a.color, b.color);
            number(what + ".intensity", a.intensity, b.intensity);
            numbers(what + ".attenuation", a.attenuation, b.attenuation);
            numbers(what + ".direction", a.direction, b.direction);
            number(what + ".beam_width", a.beam_width, b.beam_width);
            number(what + ".cut_off_angle", a.cut_off_angle, b.cut_off_angle);
            number(what + ".cut_off_exponent", a.cut_off_exponent, b.cut_off_exponent);
          } else if constexpr (std::is_same_v<T, ForceSensorParams>) {
            numbers(what + ".max_force", a.max_force, b.max_force);
            numbers(what + ".max_torque", a.max_torque, b.max_torque);
          } else if constexpr (std::is_same_v<T, InertialSensorParams>) {
            numbers(what + ".max_angular_velocity", a.max_angular_velocity, b.max_angular_velocity);
            numbers(what + ".max_acceleration", a.max_acceleration, b.max_acceleration);
          }
        },
        pa);
  }

  void device(const std::string& what, const Device& a, const Device& b) {
    text(what + ".node_type", a.node_type, b.node_type);
    text(what + ".type", a.type, b.type);
    text(what + ".name", a.name, b.name);
    equal(what + ".id", a.id, b.id);
    equal(what + ".on", a.on, b.on);
    equal(what + ".plugin", a.plugin, b.plugin);
    equal(what + ".link", a.link, b.link);
    isometry(what + ".X_LD", a.X_LD, b.X_LD);
    params(what, a.params, b.params);
    // The scalar keys of a device no stage interprets are all the model has of it: they must
    // stay, up to the spelling of keys (a renamed legacy key) and the numbers of angle keys
    // (rewritten in degrees by an upgrade, §3).
    if (std::holds_alternative<OpaqueParams>(a.params)) {
      std::map<std::string, std::string> ka, kb;
      for (const auto& [key, value] : a.keys) ka.emplace(plain_key(key), value);
      for (const auto& [key, value] : b.keys) kb.emplace(plain_key(key), value);
      for (const char* angle : {"emissionrange", "offsetrotation"}) ka.erase(angle), kb.erase(angle);
      equal(what + ".keys", ka, kb);
    }
  }

  // `offset_rotation` and `offsetRotation` alike.
  static std::string plain_key(const std::string& key) {
    std::string out;
    for (char c : key)
      if (c != '_') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
  }

 private:
  double tolerance_;
};

}  // namespace

std::optional<std::string> model_difference(const Model& a, const Model& b, double relative_tolerance) {
  Comparer c(relative_tolerance);
  c.text("name", a.name, b.name);
  c.equal("body_handlers", a.body_handlers, b.body_handlers);
  c.list("links", a.links, b.links, [&](const std::string& what, const Link& x, const Link& y) {
    const std::string named = what + " \"" + x.name + "\"";
    c.text(what + ".name", x.name, y.name);
    c.link(named, x, y);
  });
  c.list("devices", a.devices, b.devices, [&](const std::string& what, const Device& x, const Device& y) {
    c.device(what + " \"" + x.name + "\"", x, y);
  });
  c.list("extra_joints", a.extra_joints, b.extra_joints,
         [&](const std::string& what, const ExtraJoint& x, const ExtraJoint& y) {
           c.text(what + ".type", x.type, y.type);
           c.equal(what + ".link1", x.link1, y.link1);
           c.equal(what + ".link2", x.link2, y.link2);
           c.numbers(what + ".axis", x.axis, y.axis);
           c.isometry(what + ".X_1J", x.X_1J, y.X_1J);
           c.isometry(what + ".X_2J", x.X_2J, y.X_2J);
         });
  c.list("meshes", a.meshes, b.meshes, [&](const std::string& what, const MeshAsset& x, const MeshAsset& y) {
    c.text(what + ".path", x.path, y.path);
    c.text(what + ".node", x.node, y.node);
    c.count(what + ".parts", x.parts.size(), y.parts.size());
  });
  return c.difference;
}

}  // namespace bodyfmt
