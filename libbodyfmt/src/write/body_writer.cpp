#include <bodyfmt/angles.h>
#include <bodyfmt/body_writer.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/text.h>

#include <fmt/format.h>

#include <cmath>

namespace bodyfmt {
namespace {

constexpr double kDegreesPerRadian = 180.0 / kPi;

std::string quoted(std::string_view text) { return text::yaml_quote(text); }

// A comment's text: nothing in it can end the comment's line (issue 34: a newline in a file
// name added keys to the model).
std::string comment_text(std::string_view text) { return text::yaml_escape(text, false); }

void report_not_written(DiagnosticSink& sink, const SourceLocation& at, std::string_view kind, std::string what) {
  Diagnostic d =
      make_diagnostic("export-loss", at, fmt::format("the .body writer does not write {} (loss kind: {})", what, kind));
  d.category = std::string(kind);
  sink.report(std::move(d));
}

class Writer {
 public:
  Writer(const Model& model, DiagnosticSink& sink) : model_(model), sink_(sink) {}

  std::string write(const BodyWriteOptions& options) {
    if (!options.comment.empty()) line(0, "# " + comment_text(options.comment));
    line(0, "format: ChoreonoidBody");
    line(0, "format_version: 2.0");
    line(0, "angle_unit: degree");
    line(0, "name: " + quoted(model_.name));
    if (!model_.links.empty()) line(0, "root_link: " + body_string(model_.links.front().name));
    line(0, "links:");
    for (const Link& link : model_.links) write_link(link);
    for (const Device& device : model_.devices)
      report_not_written(sink_, device.source, "devices", "devices (" + device.node_type + " '" + device.name + "')");
    for (const ExtraJoint& joint : model_.extra_joints)
      report_not_written(sink_, joint.source, "closed-loops", "extra joints");
    if (!model_.body_handlers.empty()) report_not_written(sink_, model_.source, "dynamics", "body handlers");
    return std::move(out_);
  }

 private:
  void line(int indent, std::string_view text) {
    out_.append(static_cast<std::size_t>(indent), ' ');
    out_ += text;
    out_ += '\n';
  }
  static std::string vec(const Eigen::Vector3d& v) {
    return fmt::format("[ {}, {}, {} ]", body_number(v.x()), body_number(v.y()), body_number(v.z()));
  }
  // body-format-spec §4.3: a single axis-angle in degrees; empty for the identity.
  static std::string rotation(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd aa(R);
    if (aa.angle() == 0 || R == Eigen::Matrix3d::Identity()) return {};
    const Eigen::Vector3d axis = aa.axis();
    return fmt::format("[ {}, {}, {}, {} ]", body_number(axis.x()), body_number(axis.y()), body_number(axis.z()),
                       body_number(aa.angle() * kDegreesPerRadian));
  }
  static std::string limit(double value, double scale) {
    return std::abs(value) >= kUnlimited ? std::string("unlimited") : body_number(value * scale);
  }

  void write_link(const Link& link) {
    line(2, "- name: " + body_string(link.name));
    constexpr int k = 4;
    if (link.parent >= 0) line(k, "parent: " + body_string(model_.links[static_cast<std::size_t>(link.parent)].name));
    if (!link.X_PL.translation().isZero(0)) line(k, "translation: " + vec(link.X_PL.translation()));
    if (std::string r = rotation(link.X_PL.linear()); !r.empty()) line(k, "rotation: " + r);
    if (!link.joint_name.empty() && link.joint_name != link.name)
      line(k, "joint_name: " + body_string(link.joint_name));
    line(k, "joint_type: " + std::string(joint_type_name(link.joint_type)));
    const bool revolute = link.joint_type == JointType::kRevolute;
    const bool moves =
        revolute || link.joint_type == JointType::kPrismatic || link.joint_type == JointType::kPseudoContinuousTrack;
    const double unit = revolute ? kDegreesPerRadian : 1.0;
    if (moves) line(k, "joint_axis: " + vec(link.joint_axis));
    if (link.joint_id >= 0) line(k, "joint_id: " + std::to_string(link.joint_id));
    if (moves) {
      if (link.initial_displacement != 0)
        line(k, "joint_displacement: " + body_number(link.initial_displacement * unit));
      if (link.joint_range_lower > -kUnlimited || link.joint_range_upper < kUnlimited)
        line(k, fmt::format("joint_range: [ {}, {} ]", limit(link.joint_range_lower, unit),
                            limit(link.joint_range_upper, unit)));
      if (link.velocity_lower > -kUnlimited || link.velocity_upper < kUnlimited) {
        if (link.velocity_lower == -link.velocity_upper)
          line(k, "max_joint_velocity: " + body_number(link.velocity_upper * unit));
        else
          line(k, fmt::format("joint_velocity_range: [ {}, {} ]", limit(link.velocity_lower, unit),
                              limit(link.velocity_upper, unit)));
      }
      if (link.effort_upper < kUnlimited) line(k, "max_joint_effort: " + body_number(link.effort_upper));
      if (link.joint_axis_inertia != 0) line(k, "joint_axis_inertia: " + body_number(link.joint_axis_inertia));
    } else if (link.initial_displacement != 0) {
      report_not_written(sink_, link.source, "dynamics",
                         "the initial displacement of a " + std::string(joint_type_name(link.joint_type)) + " joint");
    }
    if (!link.actuation_mode.empty())
      report_not_written(sink_, link.source, "dynamics", "actuation modes ('" + link.actuation_mode.str() + "')");
    if (!link.contact_material.empty())
      report_not_written(sink_, link.source, "dynamics", "contact materials ('" + link.contact_material.str() + "')");
    if (!link.mass_contributions.empty()) {
      const MassProperties mp = compute_mass_properties(link);
      line(k, "mass: " + body_number(mp.mass));
      line(k, "center_of_mass: " + vec(mp.center_of_mass));
      std::string inertia = "inertia: [ ";
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) inertia += body_number(mp.inertia(r, c)) + (r == 2 && c == 2 ? " ]" : ", ");
      line(k, inertia);
    }
    write_shapes(link);
  }

  void write_shapes(const Link& link) {
    bool opened = false;
    int part_indent = 0;
    const Shape* run = nullptr;  // first shape of the current Visual/Collision node
    for (const Shape& shape : link.shapes) {
      if (!shape.visual && !shape.collision) continue;
      if (!writable(shape)) continue;
      if (!opened) {
        line(4, "elements:");
        opened = true;
      }
      const bool both = shape.visual && shape.collision;
      if (both) {
        run = nullptr;
        part_indent = 6;
      } else if (!run || run->visual != shape.visual) {
        line(6, std::string("- type: ") + (shape.visual ? "Visual" : "Collision"));
        line(8, "elements:");
        run = &shape;
        part_indent = 10;
      }
      write_shape(shape, part_indent);
    }
  }

  bool writable(const Shape& shape) {
    const Geometry& g = shape.geometry;
    if (geometry_is<Box>(g) || geometry_is<Sphere>(g) || geometry_is<Cylinder>(g) || geometry_is<Cone>(g) ||
        geometry_is<Capsule>(g))
      return true;
    if (const auto* mesh = geometry_if<MeshResource>(g)) {
      if (mesh->length_scale != 1.0 || mesh->y_up)
        report_not_written(sink_, mesh->uri_source, "geometry", "mesh metadata (length unit, upper axis)");
      return true;
    }
    report_not_written(sink_, shape.source, "geometry",
                       std::string(geometry_type_name(g)) + " geometry (the shape is left out)");
    return false;
  }

  void write_shape(const Shape& shape, int indent) {
    const Eigen::Matrix3d L = shape.X_LS.linear();
    // A placement that scales: a Transform node carries it (body-format-spec §4.4: R diag(s)).
    // L = R diag(scale) with R a rotation; a mirror goes into the sign of the x scale.
    Eigen::Vector3d scale(L.col(0).norm(), L.col(1).norm(), L.col(2).norm());
    Eigen::Matrix3d R = L * scale.cwiseInverse().asDiagonal();
    if (R.determinant() < 0) {
      scale.x() = -scale.x();
      R.col(0) = -R.col(0);
    }
    const bool rotation_and_scale =
        scale.cwiseAbs().minCoeff() > 0 && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-12;
    const bool rigid = rotation_and_scale && (scale.array() == 1.0).all();
    auto place = [&](int at, const Eigen::Matrix3d& rotation_part) {
      if (!shape.X_LS.translation().isZero(0)) line(at, "translation: " + vec(shape.X_LS.translation()));
      if (std::string r = rotation(rotation_part); !r.empty()) line(at, "rotation: " + r);
    };
    int at = indent;
    if (rigid) {
      line(at, "- type: Shape");
      at += 2;
      place(at, L);
    } else {
      if (!rotation_and_scale)
        report_not_written(sink_, shape.source, "geometry",
                           "a shear in a shape's placement (its rotation and per-axis scale are written)");
      line(at, "- type: Transform");
      place(at + 2, R);
      line(at + 2, "scale: " + vec(scale));
      line(at + 2, "elements:");
      at += 4;
      line(at, "- type: Shape");
      at += 2;
    }
    if (!shape.name.empty()) line(at, "name: " + body_string(shape.name));
    write_geometry(shape, at);
    if (const auto& m = shape.appearance.material.get()) {
      const Material defaults;
      line(at, "appearance:");
      line(at + 2, "material:");
      const int mi = at + 4;
      line(mi, "diffuse: " + vec(m->diffuse_color));
      if (m->ambient_intensity != defaults.ambient_intensity) line(mi, "ambient: " + body_number(m->ambient_intensity));
      if (m->emissive_color != defaults.emissive_color) line(mi, "emissive: " + vec(m->emissive_color));
      if (m->specular_color != defaults.specular_color) line(mi, "specular: " + vec(m->specular_color));
      if (m->specular_exponent != defaults.specular_exponent)
        line(mi, "specular_exponent: " + body_number(m->specular_exponent));
      if (m->transparency != defaults.transparency) line(mi, "transparency: " + body_number(m->transparency));
    }
    if (shape.appearance.texture)
      report_not_written(sink_, shape.source, "textures", "textures ('" + shape.appearance.texture->uri + "')");
  }

  void write_geometry(const Shape& shape, int at) {
    line(at, "geometry:");
    const int g = at + 2;
    const bool division = shape.division_number >= 4 && shape.division_number != 20;
    if (const auto* box = geometry_if<Box>(shape.geometry)) {
      line(g, "type: Box");
      line(g, "size: " + vec(box->size));
    } else if (const auto* sphere = geometry_if<Sphere>(shape.geometry)) {
      line(g, "type: Sphere");
      line(g, "radius: " + body_number(sphere->radius));
    } else if (const auto* cyl = geometry_if<Cylinder>(shape.geometry)) {
      line(g, "type: Cylinder");
      line(g, "radius: " + body_number(cyl->radius));
      line(g, "height: " + body_number(cyl->height));
      if (!cyl->top) line(g, "top: false");
      if (!cyl->bottom) line(g, "bottom: false");
    } else if (const auto* cone = geometry_if<Cone>(shape.geometry)) {
      line(g, "type: Cone");
      line(g, "radius: " + body_number(cone->radius));
      line(g, "height: " + body_number(cone->height));
      if (!cone->bottom) line(g, "bottom: false");
    } else if (const auto* capsule = geometry_if<Capsule>(shape.geometry)) {
      line(g, "type: Capsule");
      line(g, "radius: " + body_number(capsule->radius));
      line(g, "height: " + body_number(capsule->height));
    } else if (const auto* mesh = geometry_if<MeshResource>(shape.geometry)) {
      line(g, "type: Resource");
      line(g, "uri: " + quoted(mesh->uri));
      if (!mesh->node.empty()) line(g, "node: " + body_string(mesh->node));
    }
    if (division) line(g, "division_number: " + std::to_string(shape.division_number));
  }

  const Model& model_;
  DiagnosticSink& sink_;
  std::string out_;
};

bool plain_safe(std::string_view text) {
  if (text.empty()) return false;
  const char first = text.front();
  if (!((first >= 'A' && first <= 'Z') || (first >= 'a' && first <= 'z') || first == '_')) return false;
  for (char c : text) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
                    c == '-' || c == '.' || c == '/';
    if (!ok) return false;
  }
  // YAML 1.1 words that a reader may take for booleans or null (libyaml leaves them strings,
  // but other YAML tools do not).
  std::string lower(text);
  for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  for (std::string_view word : {"y", "n", "yes", "no", "on", "off", "true", "false", "null", "nan", "inf"})
    if (lower == word) return false;
  return true;
}

}  // namespace

std::string body_number(double value) {
  if (value == 0) return "0";  // also -0
  return fmt::format("{}", value);
}

std::string body_string(std::string_view text) { return plain_safe(text) ? std::string(text) : quoted(text); }

std::string write_body(const Model& model, const BodyWriteOptions& options, DiagnosticSink& sink) {
  return Writer(model, sink).write(options);
}

}  // namespace bodyfmt
