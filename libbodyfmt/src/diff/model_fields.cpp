#include "diff/model_fields.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/read_file.h>

#include <bodyfmt/derived.h>

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <type_traits>

namespace bodyfmt::detail {
namespace {

constexpr double kDegree = 180.0 / kPi;

std::string number_text(double x, int precision) {
  if (x == kUnlimited) return "unlimited";
  if (x == -kUnlimited) return "-unlimited";
  // -0, and the rounding noise of a cancelled sum (far below any tolerance), read as 0
  if (std::abs(x) < 1e-15) return "0";
  if (precision > 0) {
    std::string s = fmt::format("{:.{}g}", x, precision);
    return s == "-0" ? "0" : s;
  }
  return fmt::format("{}", x);
}

std::string list_text(const double* x, std::size_t n, int precision) {
  std::string out = "[";
  for (std::size_t i = 0; i < n; ++i) out += (i ? ", " : "") + number_text(x[i], precision);
  return out + "]";
}

// Choreonoid's roll-pitch-yaw (R = Rz(yaw) Ry(pitch) Rx(roll)), in degrees.
Eigen::Vector3d rpy_degrees(const Eigen::Matrix3d& R) {
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  double roll, yaw;
  if (std::abs(std::cos(pitch)) > 1e-12) {
    roll = std::atan2(R(2, 1), R(2, 2));
    yaw = std::atan2(R(1, 0), R(0, 0));
  } else {
    roll = 0;
    yaw = std::atan2(-R(0, 1), R(1, 1));
  }
  Eigen::Vector3d rpy = Eigen::Vector3d(roll, pitch, yaw) * kDegree;
  for (double& a : rpy)
    if (std::abs(a) < 1e-9) a = 0;  // rounding noise of a composed rotation, not an angle
  return rpy;
}

Field numbers_field(std::string key, FieldStyle style, std::vector<double> numbers, const SourceLocation& at) {
  Field f;
  f.key = std::move(key);
  f.style = style;
  f.numbers = std::move(numbers);
  f.source = at;
  return f;
}
Field number_field(std::string key, double x, const SourceLocation& at) {
  return numbers_field(std::move(key), FieldStyle::kNumber, {x}, at);
}
Field vector_field(std::string key, const Eigen::Vector3d& v, const SourceLocation& at) {
  return numbers_field(std::move(key), FieldStyle::kVector, {v.x(), v.y(), v.z()}, at);
}
Field range_field(std::string key, double lower, double upper, const SourceLocation& at) {
  return numbers_field(std::move(key), FieldStyle::kRange, {lower, upper}, at);
}
Field text_field(std::string key, std::string text, const SourceLocation& at) {
  Field f;
  f.key = std::move(key);
  f.text = std::move(text);
  f.source = at;
  return f;
}
template <typename Transform>
Field transform_field(std::string key, FieldStyle style, const Transform& X, const SourceLocation& at) {
  const Eigen::Matrix<double, 3, 4> M = X.matrix().template topRows<3>();
  std::vector<double> n{M(0, 3), M(1, 3), M(2, 3)};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) n.push_back(M(r, c));
  return numbers_field(std::move(key), style, std::move(n), at);
}
Field inertia_field(std::string key, const Eigen::Matrix3d& I, const SourceLocation& at) {
  std::vector<double> n(I.data(), I.data() + 9);
  return numbers_field(std::move(key), FieldStyle::kInertia, std::move(n), at);
}

void add_geometry_fields(std::vector<Field>& out, const std::string& key, const Shape& shape, MeshContents& meshes) {
  const SourceLocation& at = shape.source;
  const std::size_t first = out.size();
  out.push_back(text_field(key + " geometry", std::string(geometry_type_name(shape.geometry)), at));
  std::visit(
      [&](const auto& stored) {
        const auto& g = geometry_value(stored);
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, Box>) {
          out.push_back(vector_field(key + " size", g.size, at));
        } else if constexpr (std::is_same_v<T, Sphere>) {
          out.push_back(number_field(key + " radius", g.radius, at));
        } else if constexpr (std::is_same_v<T, Cylinder> || std::is_same_v<T, Cone> || std::is_same_v<T, Capsule>) {
          out.push_back(number_field(key + " radius", g.radius, at));
          out.push_back(number_field(key + " height", g.height, at));
          if constexpr (std::is_same_v<T, Cylinder>)
            out.push_back(text_field(key + " caps", fmt::format("top {} bottom {}", g.top, g.bottom), at));
          if constexpr (std::is_same_v<T, Cone>)
            out.push_back(text_field(key + " caps", fmt::format("bottom {}", g.bottom), at));
        } else if constexpr (std::is_same_v<T, MeshResource>) {
          Field f = text_field(key + " mesh", g.uri, g.uri_source.known() ? g.uri_source : at);
          f.compare_text = g.resolved_path.empty() ? "uri " + g.uri : meshes.content_key(g.resolved_path);
          out.push_back(std::move(f));
          if (!g.node.empty()) out.push_back(text_field(key + " mesh node", g.node, at));
          out.push_back(number_field(key + " mesh length_scale", g.length_scale, at));
          out.push_back(text_field(key + " mesh upper_axis", g.y_up ? "Y" : "Z", at));
          if (g.crease_angle) out.push_back(number_field(key + " crease_angle", *g.crease_angle, at));
        } else {
          // Extrusion, ElevationGrid, IndexedFaceSet, TriangleMesh: every number of the geometry.
          std::vector<double> n;
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
            for (const auto& o : g.orientation)
              n.insert(n.end(), {o.angle(), o.axis().x(), o.axis().y(), o.axis().z()});
            add2(g.scale);
            n.insert(n.end(), {g.crease_angle, double(g.begin_cap), double(g.end_cap)});
          } else if constexpr (std::is_same_v<T, ElevationGrid>) {
            n.insert(n.end(), {double(g.x_dimension), double(g.z_dimension), g.x_spacing, g.z_spacing});
            n.insert(n.end(), g.height.begin(), g.height.end());
            n.insert(n.end(), {double(g.ccw), g.crease_angle});
          } else {
            add3(g.vertices);
            addi(g.faces);
            add2(g.tex_coords);
            addi(g.tex_coord_indices);
            n.push_back(g.crease_angle);
          }
          Field f = numbers_field(key + " geometry data", FieldStyle::kNumber, std::move(n), at);
          f.text = fmt::format("{} numbers", f.numbers.size());
          out.push_back(std::move(f));
        }
      },
      shape.geometry);
  for (std::size_t i = first + 1; i < out.size(); ++i) out[i].geometry_detail = true;
}

// Marks the fields from `first` on as parts of `element`.
void tag(std::vector<Field>& fields, std::size_t first, const std::string& element) {
  for (std::size_t i = first; i < fields.size(); ++i) fields[i].element = element;
}

void add_shape_fields(std::vector<Field>& out, const std::string& key, const Shape& shape, MeshContents& meshes) {
  const std::size_t first = out.size();
  add_geometry_fields(out, key, shape, meshes);
  const SourceLocation& at = shape.source;
  out.push_back(transform_field(key + " placement", FieldStyle::kAffine, shape.X_LS, at));
  out.push_back(text_field(key + " role",
                           shape.visual && shape.collision ? "visual and collision"
                           : shape.visual                  ? "visual"
                           : shape.collision               ? "collision"
                                                           : "none",
                           at));
  if (shape.division_number != 20) out.push_back(number_field(key + " division_number", shape.division_number, at));
  if (const Material* m = shape.appearance.material ? &*shape.appearance.material : nullptr) {
    out.push_back(vector_field(key + " material diffuse_color", m->diffuse_color, at));
    out.push_back(vector_field(key + " material specular_color", m->specular_color, at));
    out.push_back(vector_field(key + " material emissive_color", m->emissive_color, at));
    out.push_back(number_field(key + " material ambient_intensity", m->ambient_intensity, at));
    out.push_back(number_field(key + " material specular_exponent", m->specular_exponent, at));
    out.push_back(number_field(key + " material transparency", m->transparency, at));
  }
  if (const Texture* t = shape.appearance.texture ? &*shape.appearance.texture : nullptr) {
    Field f = text_field(key + " texture", t->uri, at);
    f.compare_text = t->resolved_path.empty() ? "uri " + t->uri : meshes.content_key(t->resolved_path);
    out.push_back(std::move(f));
  }
  tag(out, first, key);
}

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

// A device no stage interprets (Holder, Conveyor, the plugin track devices of AGX and PhysX,
// ...) is compared by its scalar keys as written: numbers as numbers, so that `2.0e-4` and
// `0.0002` are the same. Lists (a track's sprocketNames) are not kept by the loader.
void add_opaque_keys(std::vector<Field>& out, const Device& d, const std::string& key) {
  std::map<std::string, std::pair<std::string, SourceLocation>> keys;
  for (const auto& [name, value] : d.keys) {
    const std::string plain = snake_case(name);
    // Read already (type, name, id, on), or an angle that --upgrade rewrites in other units.
    if (plain == "type" || plain == "name" || plain == "id" || plain == "on" || plain == "emission_range") continue;
    keys[plain] = {value, d.key_source({name})};
  }
  for (const auto& [plain, value_at] : keys) {
    const auto& [value, at] = value_at;
    char* end = nullptr;
    const double x = value.empty() ? 0 : std::strtod(value.c_str(), &end);
    if (!value.empty() && end && *end == '\0' && std::isfinite(x))
      out.push_back(number_field(key + " " + plain, x, at));
    else
      out.push_back(text_field(key + " " + plain, value, at));
  }
}

void add_device_fields(std::vector<Field>& out, const Model& model, const Device& d, const std::string& key) {
  const SourceLocation& at = d.source;
  const std::size_t first = out.size();
  out.push_back(text_field(key + " type", d.type, at));
  out.push_back(number_field(key + " id", d.id, d.key_source({"id"})));
  out.push_back(transform_field(key + " placement", FieldStyle::kPose, d.X_LD, at));
  if (!d.on) out.push_back(text_field(key + " on", "false", d.key_source({"on"})));
  std::visit(
      [&](const auto& p) {
        using T = std::decay_t<decltype(p)>;
        auto num = [&](const char* name, double x) {
          out.push_back(number_field(key + " " + name, x, d.key_source({name})));
        };
        auto vec = [&](const char* name, const Eigen::Vector3d& v) {
          out.push_back(vector_field(key + " " + name, v, d.key_source({name})));
        };
        auto txt = [&](const char* name, const std::string& s) {
          out.push_back(text_field(key + " " + name, s, d.key_source({name})));
        };
        if constexpr (std::is_same_v<T, CameraParams>) {
          txt("format", p.format);
          txt("lens_type", p.lens_type);
          num("width", p.width);
          num("height", p.height);
          num("field_of_view", p.field_of_view);
          num("near_clip_distance", p.near_clip_distance);
          num("far_clip_distance", p.far_clip_distance);
          num("frame_rate", p.frame_rate);
          txt("optical_frame", p.optical_frame);
          out.push_back(inertia_field(key + " optical_frame_rotation", p.optical_frame_rotation, at));
          out.back().style = FieldStyle::kNumber;
          num("min_distance", p.min_distance);
          num("max_distance", p.max_distance);
          num("detection_rate", p.detection_rate);
          num("error_deviation", p.error_deviation);
        } else if constexpr (std::is_same_v<T, RangeSensorParams>) {
          num("yaw_range", p.yaw_range);
          num("yaw_step", p.yaw_step);
          num("pitch_range", p.pitch_range);
          num("pitch_step", p.pitch_step);
          num("min_distance", p.min_distance);
          num("max_distance", p.max_distance);
          num("scan_rate", p.scan_rate);
          num("detection_rate", p.detection_rate);
          num("error_deviation", p.error_deviation);
        } else if constexpr (std::is_same_v<T, LightParams>) {
          vec("color", p.color);
          num("intensity", p.intensity);
          vec("attenuation", p.attenuation);
          vec("direction", p.direction);
          num("beam_width", p.beam_width);
          num("cut_off_angle", p.cut_off_angle);
          num("cut_off_exponent", p.cut_off_exponent);
        } else if constexpr (std::is_same_v<T, ForceSensorParams>) {
          vec("max_force", p.max_force);
          vec("max_torque", p.max_torque);
        } else if constexpr (std::is_same_v<T, InertialSensorParams>) {
          vec("max_angular_velocity", p.max_angular_velocity);
          vec("max_acceleration", p.max_acceleration);
        } else if constexpr (std::is_same_v<T, OpaqueParams>) {
          add_opaque_keys(out, d, key);
        }
      },
      d.params);
  (void)model;
  tag(out, first, key);
}

}  // namespace

std::string MeshContents::content_key(const std::string& path) {
  if (path.empty()) return {};
  auto it = cache_.find(path);
  if (it != cache_.end()) return it->second;
  std::string why, key;
  if (auto bytes = read_regular_file(path, std::uintmax_t(1) << 30, why))
    key = fmt::format("{} bytes, hash {:016x}", bytes->size(), std::hash<std::string>()(*bytes));
  else
    key = "unreadable: " + why;
  return cache_.emplace(path, key).first->second;
}

FieldCollector::FieldCollector(const Model& model, bool derived)
    : model_(model), derived_(derived && !model.links.empty()) {  // an absent model (git: a new file) has none
  if (model.links.empty()) return;                                // no model at all: a file that git adds or deletes
  model_fields_.push_back(text_field("name", model.name, model.source));
  if (derived_) {
    // Geometry and overflow problems are bodycheck's to report; a shape that cannot be
    // tessellated adds nothing to the boxes.
    struct Ignored : DiagnosticSink {
      void report(Diagnostic) override {}
    } ignored;
    data_ = compute_derived(model, ignored);
    const double total = data_.total_mass;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < model.links.size(); ++i)
      moment += data_.mass[i].mass * (as_isometry(data_.X_WL[i]) * data_.mass[i].center_of_mass);
    model_fields_.push_back(number_field("total_mass", total, model.source));
    model_fields_.back().derived = true;
    model_fields_.push_back(
        vector_field("center_of_mass", total != 0 ? Eigen::Vector3d(moment / total) : moment, model.source));
    model_fields_.back().derived = true;
  } else {
    data_.mass.reserve(model.links.size());
    for (const Link& link : model.links) data_.mass.push_back(compute_mass_properties(link));
  }
  for (std::size_t i = 0; i < model.extra_joints.size(); ++i) {
    const ExtraJoint& j = model.extra_joints[i];
    const std::string key = fmt::format("extra_joint {}", i);
    model_fields_.push_back(
        text_field(key, fmt::format("{} '{}' '{}'", j.type, link_name(j.link1), link_name(j.link2)), j.source));
    model_fields_.push_back(vector_field(key + " axis", j.axis, j.source));
    model_fields_.push_back(transform_field(key + " link1 frame", FieldStyle::kPose, j.X_1J, j.source));
    model_fields_.push_back(transform_field(key + " link2 frame", FieldStyle::kPose, j.X_2J, j.source));
    for (std::size_t k = model_fields_.size() - 4; k < model_fields_.size(); ++k) model_fields_[k].element = key;
  }
  // Devices under their link, by name (or type and rank when unnamed).
  devices_.resize(model.links.size());
  std::map<std::string, int> unnamed;
  for (const Device& d : model.devices) {
    if (d.link < 0 || d.link >= static_cast<LinkIndex>(model.links.size())) continue;
    devices_[d.link].emplace_back(&d, d.name.empty() ? fmt::format("device {}#{}", d.node_type, unnamed[d.node_type]++)
                                                     : "device '" + d.name + "'");
  }
}

std::string FieldCollector::link_name(LinkIndex i) const { return i >= 0 ? model_.links[i].name : std::string(); }

LinkFields FieldCollector::link(std::size_t i) {
  const Link& link = model_.links[i];
  LinkFields lf;
  lf.name = link.name;
  lf.source = source_of(link, LinkSources::kName);
  lf.summary = link.parent >= 0
                   ? fmt::format("{} joint under '{}'", joint_type_name(link.joint_type), link_name(link.parent))
                   : fmt::format("root, {} joint", joint_type_name(link.joint_type));
  auto& f = lf.fields;
  f.push_back(text_field("parent", link_name(link.parent), source_of(link, LinkSources::kParent)));
  if (!link.joint_name.empty()) f.push_back(text_field("joint_name", link.joint_name, link.source));
  f.push_back(vector_field("translation", link.X_PL.translation(), source_of(link, LinkSources::kTranslation)));
  {
    const Eigen::Matrix3d R = link.X_PL.linear();
    f.push_back(numbers_field("rotation", FieldStyle::kPose, {0, 0, 0}, source_of(link, LinkSources::kRotation)));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) f.back().numbers.push_back(R(r, c));
  }
  f.push_back(text_field("joint_type", std::string(joint_type_name(link.joint_type)),
                         source_of(link, LinkSources::kJointType)));
  if (link.joint_type != JointType::kFixed && link.joint_type != JointType::kFree) {
    f.push_back(vector_field("joint_axis", link.joint_axis, source_of(link, LinkSources::kJointAxis)));
    f.push_back(range_field("joint_range", link.joint_range_lower, link.joint_range_upper,
                            source_of(link, LinkSources::kJointRange)));
    if (link.joint_type == JointType::kRevolute) f.back().style = FieldStyle::kAngleRange;
    f.push_back(range_field("joint_velocity_range", link.velocity_lower, link.velocity_upper,
                            source_of(link, LinkSources::kJointVelocity)));
    f.push_back(range_field("joint_effort_range", link.effort_lower, link.effort_upper, link.source));
    f.push_back(number_field("joint_axis_inertia", link.joint_axis_inertia, link.source));
    f.push_back(number_field("initial_displacement", link.initial_displacement, link.source));
  }
  f.push_back(number_field("joint_id", link.joint_id, source_of(link, LinkSources::kJointId)));
  if (!link.actuation_mode.empty()) f.push_back(text_field("actuation_mode", link.actuation_mode, link.source));
  if (!link.contact_material.empty()) f.push_back(text_field("material", link.contact_material, link.source));
  f.push_back(number_field("mass", data_.mass[i].mass,
                           first_known({link.sources.mass(), rigid_body_source(link), link.source})));
  f.push_back(vector_field("center_of_mass", data_.mass[i].center_of_mass,
                           first_known({link.sources.center_of_mass(), rigid_body_source(link), link.source})));
  f.push_back(inertia_field("inertia", data_.mass[i].inertia, inertia_source(link)));
  for (std::size_t s = 0; s < link.shapes.size(); ++s)
    add_shape_fields(f, fmt::format("shape {}", s), link.shapes[s], meshes_);
  if (derived_) {
    f.push_back(transform_field("world_frame", FieldStyle::kPose, as_isometry(data_.X_WL[i]), lf.source));
    f.back().derived = true;
    auto box = [&](const char* key, const BoundingBox& b) {
      if (b.empty()) return;
      f.push_back(numbers_field(key, FieldStyle::kBox,
                                {b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z()}, lf.source));
      f.back().derived = true;
    };
    box("visual_bounding_box", data_.bounds[i].visual);
    box("collision_bounding_box", data_.bounds[i].collision);
  }
  for (const auto& [device, key] : devices_[i]) add_device_fields(f, model_, *device, key);
  return lf;
}

std::string field_value(const Field& field, int precision) {
  const std::vector<double>& n = field.numbers;
  std::string numbers;
  switch (field.style) {
    case FieldStyle::kText: return field.text;
    case FieldStyle::kNumber:
      if (n.size() > 12 && !field.text.empty()) return field.text;  // a mesh's numbers
      numbers = n.size() == 1 ? number_text(n[0], precision) : list_text(n.data(), n.size(), precision);
      break;
    case FieldStyle::kVector:
    case FieldStyle::kRange: numbers = list_text(n.data(), n.size(), precision); break;
    case FieldStyle::kAngleRange: {
      // The file writes degrees (format 2.0 and most 1.0 files): show them beside the radians.
      const double degrees[] = {std::abs(n[0]) == kUnlimited ? n[0] : n[0] * kDegree,
                                std::abs(n[1]) == kUnlimited ? n[1] : n[1] * kDegree};
      numbers = list_text(n.data(), n.size(), precision) + " rad = " + list_text(degrees, 2, 12) + " deg";
      break;
    }
    case FieldStyle::kPose:
    case FieldStyle::kAffine: {
      Eigen::Matrix3d R;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) R(r, c) = n[3 + 3 * r + c];
      const bool rigid = (R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0;
      const bool translated = field.key != "rotation";
      if (translated) numbers = "xyz " + list_text(n.data(), 3, precision);
      if (rigid) {
        const Eigen::Vector3d rpy = rpy_degrees(R);
        numbers +=
            (translated ? " rpy " : "rpy ") + list_text(rpy.data(), 3, precision > 0 ? precision - 3 : 0) + " deg";
      } else {
        numbers += " linear " + list_text(n.data() + 3, 9, precision);
      }
      break;
    }
    case FieldStyle::kBox:
      numbers = "min " + list_text(n.data(), 3, precision) + " max " + list_text(n.data() + 3, 3, precision);
      break;
    case FieldStyle::kInertia: {
      const double six[] = {n[0], n[3], n[6], n[4], n[7], n[8]};
      numbers = list_text(six, 6, precision);
      break;
    }
  }
  return field.text.empty() ? numbers : field.text + " " + numbers;
}

bool same_value(const Field& a, const Field& b, double tolerance) {
  if (a.style != b.style) return false;
  const std::string& ta = a.compare_text.empty() ? a.text : a.compare_text;
  const std::string& tb = b.compare_text.empty() ? b.text : b.compare_text;
  if (ta != tb || a.numbers.size() != b.numbers.size()) return false;
  for (std::size_t i = 0; i < a.numbers.size(); ++i) {
    const double x = a.numbers[i], y = b.numbers[i];
    if (x == y || (std::isnan(x) && std::isnan(y))) continue;
    if (!std::isfinite(x) || !std::isfinite(y)) return false;
    if (std::abs(x - y) > tolerance * std::max({1.0, std::abs(x), std::abs(y)})) return false;
  }
  return true;
}

}  // namespace bodyfmt::detail
