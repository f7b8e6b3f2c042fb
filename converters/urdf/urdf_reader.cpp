#include "urdf_reader.h"

#include "mesh_lookup.h"
#include "xml_positions.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/converters/loss.h>
#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/text.h>

#include <fmt/format.h>

#include <tinyxml2.h>
#include <type_traits>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <unordered_map>

namespace bodyfmt::urdf_import {
namespace {

namespace fs = std::filesystem;
using converters::LossKind;
using tinyxml2::XMLElement;

constexpr std::string_view kTarget = "a Choreonoid .body";

bool named(const XMLElement* e, const char* name) { return std::strcmp(e->Name(), name) == 0; }

struct JointInfo {
  const XMLElement* element = nullptr;
  std::string name;
  std::string parent;
  std::string child;
};

/// The <robot>'s links and joints by name, in document order.
struct Elements {
  std::vector<const XMLElement*> links;
  std::vector<JointInfo> joints;
  std::unordered_map<std::string, std::size_t> link_index;
  std::unordered_map<std::string, std::size_t> joint_index;
};

/// How the joints connect the links (indices into Elements).
struct Tree {
  std::vector<int> parent_joint;               ///< per link: its joint, or -1 for a root
  std::vector<std::vector<int>> child_joints;  ///< per link, in document order
  std::vector<std::size_t> roots;
  std::size_t root = 0;  ///< the link the model starts from
  int root_joint = -1;   ///< the joint from an empty "world" link to `root`, or -1
};

class Reader {
 public:
  Reader(std::string_view text, const std::string& file, const UrdfImportOptions& options, DiagnosticSink& sink)
      : text_(text), file_(file), options_(options), sink_(sink), at_(text, file) {
    search_.package_paths = options.package_paths;
    search_.use_ros_package_path = options.use_ros_package_path;
    search_.referring_folder = fs::path(file).parent_path();
    if (options.confine_meshes) urdf_tree_ = package_tree(search_.referring_folder);
    std::error_code ec;
    output_folder_ =
        fs::absolute(options.output_folder.empty() ? fs::path(".") : options.output_folder, ec).lexically_normal();
  }

  std::optional<Model> read();

 private:
  Elements collect(const XMLElement* robot);
  void collect_visual_materials(const Elements& elements);
  std::optional<Tree> connect(const Elements& elements);
  void choose_root(const Elements& elements, Tree& tree);
  std::vector<bool> build_links(const Elements& elements, const Tree& tree, Model& model);
  void report_cycles(const Elements& elements, const Tree& tree, const std::vector<bool>& visited);

  void report(std::string_view rule, const SourceLocation& at, std::string message, std::string hint = {}) {
    report_rule(sink_, rule, at, std::move(message), std::move(hint));
  }
  void loss(const SourceLocation& at, LossKind kind, std::string_view what, std::string_view hint = {}) {
    converters::report_loss(sink_, at, kTarget, kind, what, hint);
  }

  // Values. Each reports `import-value` at the attribute and returns nullopt when it does not read.
  std::optional<std::vector<double>> numbers(const XMLElement* e, const char* attribute, std::size_t count);
  std::optional<double> number(const XMLElement* e, const char* attribute);
  std::optional<Eigen::Vector3d> vec3(const XMLElement* e, const char* attribute) {
    auto v = numbers(e, attribute, 3);
    if (!v) return std::nullopt;
    return Eigen::Vector3d((*v)[0], (*v)[1], (*v)[2]);
  }
  std::string required_name(const XMLElement* e, const char* attribute, const char* what);
  void check_text(const XMLElement* e, const char* attribute);
  bool check_document();
  Eigen::Isometry3d origin(const XMLElement* parent);

  void read_material(const XMLElement* e, bool top_level);
  void read_link(const XMLElement* e, Link& link);
  void read_link_shapes(const XMLElement* e, Link& link);
  void read_inertial(const XMLElement* e, Link& link);
  void read_shape(const XMLElement* e, Link& link, bool visual);
  std::optional<Geometry> read_geometry(const XMLElement* geometry, Eigen::Isometry3d& X_LS, Eigen::Vector3d& scale);
  void read_joint(const JointInfo& joint, Link& link, bool is_root_child_of_world);
  void report_unknown_children(const XMLElement* e, std::initializer_list<const char*> known, const char* where);
  // Conventions outside the URDF spec that ROS tools and simulators accept (each an import-convention warning).
  void convention(const SourceLocation& at, std::string message) {
    report("import-convention", at, std::move(message));
  }
  std::optional<double> product_of_inertia(const XMLElement* inertia, const char* attribute);
  void report_reversed_range(const XMLElement* limit, const std::string& joint, double lower, double upper);
  bool unusable_size(const XMLElement* shape, const char* attribute, double value, bool zero_allowed);
  void report_world_content(const XMLElement* world);
  void read_fixed_axis(const XMLElement* joint, Link& link);

  /// A wrapper body file: the model is read as Choreonoid's URDF loader reads it.
  bool choreonoid() const { return options_.semantics == UrdfSemantics::kChoreonoid; }
  /// Where Choreonoid's URDF loader reads the text differently from the URDF spec: a warning in
  /// a wrapper (the model follows Choreonoid), a note in urdf2body (the model follows the URDF).
  /// A wrapper's warning has a rule of its own for each kind, so that one can be disabled and
  /// none hides another when a report folds the repeats of a rule.
  enum class Difference { kMass, kWorld, kOther };
  void differs(Difference kind, const SourceLocation& at, std::string message, std::string hint = {}) {
    const char* rule = !choreonoid()                ? "import-choreonoid-differs"
                       : kind == Difference::kMass  ? "wrapper-urdf-mass"
                       : kind == Difference::kWorld ? "wrapper-urdf-world"
                                                    : "wrapper-urdf-semantics";
    report(rule, at, std::move(message), std::move(hint));
  }
  /// What Choreonoid's URDF loader refuses (it loads no body): an error in a wrapper only.
  void refused(const SourceLocation& at, const std::string& what) {
    report("wrapper-urdf-refused", at,
           what + ": Choreonoid's URDF loader refuses the file, so this wrapper body file does not load in Choreonoid");
  }
  std::string mesh_uri(const XMLElement* mesh, const std::string& filename, std::string& resolved);

  std::string_view text_;
  std::string file_;
  const UrdfImportOptions& options_;
  DiagnosticSink& sink_;
  XmlPositions at_;
  PackageSearch search_;
  fs::path urdf_tree_;  ///< where confined meshes may be (UrdfImportOptions::confine_meshes)
  fs::path output_folder_;
  std::map<std::string, Material> materials_;
  std::unordered_map<std::string, std::pair<std::string, std::string>> mesh_cache_;  // uri -> relative, resolved
  std::unordered_map<std::string, bool> mesh_reported_;
  std::size_t links_without_inertial_ = 0;
};

// Choreonoid's URDF loader reads a vector number by number, each followed by spaces and at most
// one comma (cnoid::toVector3 in src/Util/EigenUtil.cpp; toVector4 for colours), so that
// "0.07, 0, -0.69" is three numbers there; urdfdom splits at spaces and refuses "0.07,". Returns
// nullopt where that reading fails too (a doubled comma, a missing number, one too many).
std::optional<std::vector<double>> comma_separated(const char* text, std::size_t count) {
  const char* p = text;
  const char* end = text + std::strlen(text);
  auto space = [](char c) { return c != 0 && std::strchr(" \t\r\n\v\f", c) != nullptr; };
  std::vector<double> values;
  for (std::size_t i = 0; i < count; ++i) {
    while (p < end && space(*p)) ++p;
    const bool plus = p < end && *p == '+';
    if (plus) ++p;
    double v = 0;
    auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc() || (plus && (*p == '-' || *p == '+')) || !std::isfinite(v)) return std::nullopt;
    values.push_back(v);
    p = next;
    while (p < end && space(*p)) ++p;
    if (p < end && *p == ',') ++p;
  }
  while (p < end && space(*p)) ++p;
  if (p != end) return std::nullopt;
  return values;
}

std::optional<std::vector<double>> Reader::numbers(const XMLElement* e, const char* attribute, std::size_t count) {
  const char* text = e->Attribute(attribute);
  if (!text) return std::nullopt;
  if (count > 1 && std::strchr(text, ','))
    if (auto v = comma_separated(text, count)) {
      std::string read;
      for (double x : *v) read += (read.empty() ? "" : " ") + converters::format_number(x);
      convention(at_.at(e, attribute),
                 fmt::format("{}=\"{}\" separates its numbers with commas: read as Choreonoid's URDF loader reads it, "
                             "\"{}\" (urdfdom and the ROS tools refuse it)",
                             attribute, text, read));
      return v;
    }
  std::vector<double> values;
  const char* p = text;
  const char* end = text + std::strlen(text);
  while (true) {
    while (p < end && std::strchr(" \t\r\n", *p)) ++p;
    if (p == end) break;
    // from_chars takes no plus sign; URDF writers do emit them. "+-1" is not a number.
    const bool plus = *p == '+';
    if (plus) ++p;
    double v = 0;
    auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc() || (plus && p < end && (*p == '-' || *p == '+')) ||
        (next < end && !std::strchr(" \t\r\n", *next)) || !std::isfinite(v)) {
      report("import-value", at_.at(e, attribute),
             fmt::format("{}=\"{}\" is not {}", attribute, text,
                         count == 1 ? "a finite number" : fmt::format("{} finite numbers", count)));
      return std::nullopt;
    }
    values.push_back(v);
    p = next;
  }
  if (values.size() != count) {
    report("import-value", at_.at(e, attribute),
           fmt::format("{}=\"{}\" has {} numbers, {} expected", attribute, text, values.size(), count));
    return std::nullopt;
  }
  return values;
}

std::optional<double> Reader::number(const XMLElement* e, const char* attribute) {
  auto v = numbers(e, attribute, 1);
  if (!v) return std::nullopt;
  return v->front();
}

std::string Reader::required_name(const XMLElement* e, const char* attribute, const char* what) {
  const char* value = e->Attribute(attribute);
  if (!value || !*value) {
    report("import-structure", at_.at(e), fmt::format("this {} has no {} attribute", what, attribute));
    return {};
  }
  check_text(e, attribute);
  return value;
}

// A text the .body keeps must come back byte for byte: the writer escapes every character
// YAML cannot hold as it is, but a byte that is not UTF-8 has no YAML spelling.
void Reader::check_text(const XMLElement* e, const char* attribute) {
  const char* value = e->Attribute(attribute);
  if (value && !text::is_utf8(value))
    report("import-value", at_.at(e, attribute),
           fmt::format("{}=\"{}\" is not valid UTF-8 (a .body file is UTF-8; a character reference such as "
                       "&#xD800; or &#x110000; names no character)",
                       attribute, value));
}

// URDF's origin: xyz, then rpy as R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Isometry3d Reader::origin(const XMLElement* parent) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const XMLElement* o = parent->FirstChildElement("origin");
  if (!o) return X;
  if (auto xyz = vec3(o, "xyz")) X.translation() = *xyz;
  if (auto rpy = vec3(o, "rpy"))
    X.linear() =
        (Eigen::AngleAxisd(rpy->z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy->y(), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(rpy->x(), Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
  return X;
}

void Reader::report_unknown_children(const XMLElement* e, std::initializer_list<const char*> known, const char* where) {
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    bool is_known = false;
    for (const char* k : known) is_known = is_known || named(c, k);
    if (!is_known)
      report("import-unknown-element", at_.at(c),
             fmt::format("<{}> in a {} is not URDF; it is ignored", c->Name(), where));
  }
}

// urdfdom requires all six attributes; Drake and MuJoCo read a missing product of inertia as 0,
// and files written for them leave the zeros out.
std::optional<double> Reader::product_of_inertia(const XMLElement* inertia, const char* attribute) {
  if (inertia->Attribute(attribute)) return number(inertia, attribute);
  if (choreonoid()) {
    refused(at_.at(inertia), fmt::format("<inertia> has no {} attribute", attribute));
    return 0.0;
  }
  convention(at_.at(inertia), fmt::format("<inertia> has no {} attribute; read as 0, as Drake and MuJoCo do (urdfdom "
                                          "refuses it)",
                                          attribute));
  return 0.0;
}

// Kept as written, as urdfdom keeps it (Choreonoid accepts it too, and body2urdf writes it back);
// MuJoCo's URDF import reads the joint as unlimited and Drake refuses it.
void Reader::report_reversed_range(const XMLElement* limit, const std::string& joint, double lower, double upper) {
  convention(at_.at(limit, "lower"),
             fmt::format("joint '{}' has lower {} > upper {}; kept as written (urdfdom keeps it, MuJoCo reads the "
                         "joint as unlimited, Drake refuses it; bodycheck reports joint-range-reversed)",
                         joint, converters::format_number(lower), converters::format_number(upper)));
}

// A size the Body format cannot hold must not reach the written file, which would then fail to
// load: a zero radius or cylinder length (feet's contact points; a point or a disc to urdfdom and
// Gazebo) leaves the shape out as a reported loss, since Choreonoid refuses a size that is not
// positive; a negative size is no shape at all and is an error at its attribute.
bool Reader::unusable_size(const XMLElement* shape, const char* attribute, double value, bool zero_allowed) {
  // Choreonoid's mesh generator makes no mesh of a negative box edge, nor of a sphere or cylinder
  // whose radius or length is not positive; the URDF loader keeps the empty shape node and loads
  // on (a box with a zero edge is a flat mesh there, as here).
  if (choreonoid() && (value < 0 || (value == 0 && !zero_allowed))) {
    differs(Difference::kOther, at_.at(shape, attribute),
            fmt::format("<{}> has {} {}: Choreonoid's URDF loader makes no shape of it (its mesh generator refuses a "
                        "{} size) and loads on",
                        shape->Name(), attribute, converters::format_number(value), value < 0 ? "negative" : "zero"),
            "remove the shape, or give it a positive size");
    return true;
  }
  if (value < 0) {
    report("import-value", at_.at(shape, attribute),
           fmt::format("<{}> has a negative {} ({})", shape->Name(), attribute, converters::format_number(value)));
    return true;
  }
  if (value > 0 || zero_allowed) return false;
  loss(at_.at(shape, attribute), LossKind::kGeometry,
       fmt::format("the <{}> of {} 0 (a point or a flat shape to urdfdom and Gazebo; Choreonoid refuses a size that "
                   "is not positive, so the shape is left out)",
                   shape->Name(), attribute));
  return true;
}

// What a folded `world` link holds is not part of the robot: consumers take `world` as the fixed
// frame, and a .body has no link above its root to hold it.
void Reader::report_world_content(const XMLElement* world) {
  for (const XMLElement* c = world->FirstChildElement(); c; c = c->NextSiblingElement())
    loss(at_.at(c), named(c, "inertial") ? LossKind::kDynamics : LossKind::kGeometry,
         fmt::format("the <{}> of the 'world' link (the world is the fixed frame: its child is the root of the body)",
                     c->Name()));
}

void Reader::read_material(const XMLElement* e, bool top_level) {
  const char* name = e->Attribute("name");
  const XMLElement* color = e->FirstChildElement("color");
  if (const XMLElement* texture = e->FirstChildElement("texture"))
    loss(at_.at(texture), LossKind::kTextures,
         fmt::format("the texture '{}'", texture->Attribute("filename") ? texture->Attribute("filename") : ""),
         "the colour is kept");
  if (!color) {
    if (top_level && !e->FirstChildElement("texture"))
      report("import-structure", at_.at(e), "a top-level <material> needs a <color>");
    return;
  }
  auto rgba = numbers(color, "rgba", 4);
  if (!rgba) {
    if (!color->Attribute("rgba")) report("import-structure", at_.at(color), "<color> has no rgba attribute");
    return;
  }
  Material m;
  m.diffuse_color = Eigen::Vector3d((*rgba)[0], (*rgba)[1], (*rgba)[2]);
  m.transparency = 1.0 - (*rgba)[3];
  if (name && *name) materials_.emplace(name, m);  // the first definition wins, as in urdfdom
}

void Reader::read_inertial(const XMLElement* e, Link& link) {
  MassContribution c;
  c.from_link_keys = true;
  c.source = at_.at(e);
  const Eigen::Isometry3d X_LC = origin(e);
  c.center_of_mass = X_LC.translation();
  if (const XMLElement* o = e->FirstChildElement("origin")) {
    link.sources.set(LinkSources::kCenterOfMass, at_.at(o));
  }
  const XMLElement* mass = e->FirstChildElement("mass");
  if (!mass) {
    report("import-structure", at_.at(e), "this <inertial> has no <mass>");
  } else if (auto m = number(mass, "value")) {
    c.mass = *m;
    link.sources.set(LinkSources::kMass, at_.at(mass, "value"));
    c.source = at_.at(mass, "value");
    if (*m < 0)
      report("import-mass", at_.at(mass, "value"), fmt::format("link '{}' has a negative mass {}", link.name, *m));
    else if (*m == 0 && choreonoid())
      refused(at_.at(mass, "value"), fmt::format("link '{}' has mass 0 (its <inertial> needs a positive mass; a "
                                                 "link without <inertial> is read as 1 kg)",
                                                 link.name));
  } else if (!mass->Attribute("value")) {
    report("import-structure", at_.at(mass), "<mass> has no value attribute");
  }
  const XMLElement* inertia = e->FirstChildElement("inertia");
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  if (!inertia && choreonoid()) {
    I = Eigen::Matrix3d::Identity();
    differs(Difference::kMass, at_.at(e),
            fmt::format("this <inertial> has no <inertia>: Choreonoid's URDF loader gives link '{}' identity inertia "
                        "(1 kg·m² about each axis; urdfdom refuses it)",
                        link.name),
            "add <inertia ixx ixy ixz iyy iyz izz>");
  } else if (!inertia) {
    report("import-structure", at_.at(e), "this <inertial> has no <inertia>");
  } else {
    link.sources.set(LinkSources::kInertia, at_.at(inertia));
    const char* names[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
    double v[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < 6; ++i) {
      if (i == 1 || i == 2 || i == 4) {
        v[i] = product_of_inertia(inertia, names[i]).value_or(0);
        continue;
      }
      if (!inertia->Attribute(names[i])) {
        report("import-structure", at_.at(inertia), fmt::format("<inertia> has no {} attribute", names[i]));
        continue;
      }
      if (auto x = number(inertia, names[i])) v[i] = *x;
    }
    I << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
    // A negative moment beyond rounding (exporters write -5e-20 for a zero, which bodycheck's
    // inertia rules report as a zero inertia).
    const double largest = std::max({std::abs(v[0]), std::abs(v[3]), std::abs(v[5])});
    for (int i : {0, 3, 5})
      if (v[i] < -std::max(1e-9 * largest, 1e-12))
        report("import-mass", at_.at(inertia, names[i]),
               fmt::format("link '{}' has a negative moment of inertia {}={}", link.name, names[i], v[i]));
  }
  // The tensor is given in the inertial frame; the link keeps it in link axes (rpy rotates it).
  c.inertia = X_LC.linear() * I * X_LC.linear().transpose();
  // (Choreonoid's URDF loader refuses a mass of 0: reported above, in a wrapper.)
  if (c.mass == 0 && !choreonoid() && (!I.isZero(0) || !c.center_of_mass.isZero(0)))
    loss(c.source, LossKind::kDynamics,
         fmt::format("the inertia and centre of mass of the massless link '{}' (Choreonoid ignores both when the "
                     "mass is 0, body-format-spec §6.4)",
                     link.name));
  link.mass_contributions.push_back(c);
}

std::string Reader::mesh_uri(const XMLElement* mesh, const std::string& filename, std::string& resolved) {
  if (!options_.resolve_meshes) {
    // Kept as written: it must still be a URI the .body loader takes (found by fuzz_urdf_import:
    // "meshes/a://b" made a file that did not load).
    const std::string_view path =
        std::string_view(filename).substr(filename.rfind("file://", 0) == 0 ? std::strlen("file://") : 0);
    if (const std::size_t scheme = path.find("://");
        scheme != std::string_view::npos && path.substr(0, scheme) != "package")
      report("import-mesh", at_.at(mesh, "filename"),
             fmt::format("the URI scheme {}:// of the mesh '{}' is not supported (package://, file:// and paths are)",
                         path.substr(0, scheme), filename));
    return filename;
  }
  auto cached = mesh_cache_.find(filename);
  if (cached == mesh_cache_.end()) {
    PackageLookup found = find_mesh(filename, search_);
    std::string relative;
    if (!found.path.empty() && options_.confine_meshes && !inside_tree(found.path, urdf_tree_) &&
        (found.package_folder.empty() || !inside_tree(found.path, fs::weakly_canonical(found.package_folder)))) {
      report("import-mesh", at_.at(mesh, "filename"),
             fmt::format("the mesh '{}' is the file '{}', outside the URDF's folder tree '{}'{}; --copy-meshes copies "
                         "only files inside it",
                         filename, found.path, urdf_tree_.string(),
                         found.package_folder.empty() ? "" : " and the package '" + found.package_folder + "'"));
      found.path.clear();
    } else if (!found.path.empty()) {
      relative = fs::path(found.path).lexically_relative(output_folder_).generic_string();
      if (relative.empty()) relative = fs::path(found.path).generic_string();
    } else {
      std::string message = fmt::format("the mesh '{}' cannot be found", filename);
      if (!found.problem.empty()) message += ": " + found.problem;
      if (!found.searched.empty()) {
        message += "; searched:";
        for (const std::string& place : found.searched) message += "\n  " + place;
      }
      report("import-mesh", at_.at(mesh, "filename"), message,
             filename.rfind("package://", 0) == 0 ? "give the folder holding the package with --package-path" : "");
    }
    cached = mesh_cache_.emplace(filename, std::make_pair(relative, found.path)).first;
  } else if (cached->second.second.empty()) {
    report("import-mesh", at_.at(mesh, "filename"), fmt::format("the mesh '{}' cannot be found (see above)", filename));
  }
  resolved = cached->second.second;
  return cached->second.first.empty() ? filename : cached->second.first;
}

std::optional<Geometry> Reader::read_geometry(const XMLElement* g, Eigen::Isometry3d& X_LS, Eigen::Vector3d& scale) {
  const XMLElement* shape = g->FirstChildElement();
  if (!shape) {
    report("import-structure", at_.at(g), "this <geometry> is empty");
    return std::nullopt;
  }
  if (const XMLElement* extra = shape->NextSiblingElement(); extra && choreonoid())
    refused(at_.at(extra), fmt::format("a second shape <{}> in one <geometry>", extra->Name()));
  else if (extra)
    convention(at_.at(extra), fmt::format("a <geometry> holds one shape; this <{}> is ignored (urdfdom, Gazebo and "
                                          "MoveIt take the first, <{}>)",
                                          extra->Name(), shape->Name()));
  auto require = [&](const char* attribute) -> std::optional<double> {
    if (!shape->Attribute(attribute)) {
      report("import-structure", at_.at(shape), fmt::format("<{}> has no {} attribute", shape->Name(), attribute));
      return std::nullopt;
    }
    return number(shape, attribute);
  };
  if (named(shape, "box")) {
    if (!shape->Attribute("size")) {
      report("import-structure", at_.at(shape), "<box> has no size attribute");
      return std::nullopt;
    }
    auto size = vec3(shape, "size");
    if (!size) return std::nullopt;
    // A zero edge is a flat box, which the Body format holds (bodycheck warns geometry-zero-size).
    if (unusable_size(shape, "size", size->minCoeff(), /*zero_allowed=*/true)) return std::nullopt;
    return Geometry(Box{*size});
  }
  if (named(shape, "sphere")) {
    auto r = require("radius");
    if (!r || unusable_size(shape, "radius", *r, false)) return std::nullopt;
    return Geometry(Sphere{*r});
  }
  // URDF's cylinder and capsule run along Z, Choreonoid's along Y: Rx(+90°) maps +Y onto +Z
  // (written with exact zeros and ones, so that nothing but the origin's rounding enters).
  auto along_z = [&](auto round_shape) -> std::optional<Geometry> {
    auto r = require("radius");
    auto h = require("length");
    if (!r || !h || unusable_size(shape, "radius", *r, false)) return std::nullopt;
    // A capsule of length 0 is a sphere; a cylinder of length 0 is a disc, which Choreonoid refuses.
    if (unusable_size(shape, "length", *h, std::is_same_v<decltype(round_shape), Capsule>)) return std::nullopt;
    Eigen::Matrix3d Rx90;
    Rx90 << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    X_LS.linear() = X_LS.linear() * Rx90;
    round_shape.radius = *r;
    round_shape.height = *h;
    return Geometry(round_shape);
  };
  if (named(shape, "cylinder")) return along_z(Cylinder{});
  if (named(shape, "mesh")) {
    const char* filename = shape->Attribute("filename");
    if (!filename || !*filename) {
      report("import-structure", at_.at(shape), "<mesh> has no filename attribute");
      return std::nullopt;
    }
    if (shape->Attribute("scale"))
      if (auto s = vec3(shape, "scale")) {
        // A zero factor flattens the mesh: its placement has no rotation to write.
        if ((s->array() == 0).any())
          report(
              "import-value", at_.at(shape, "scale"),
              fmt::format("scale=\"{}\" has a zero factor (a mesh cannot be scaled flat)", shape->Attribute("scale")));
        else
          scale = *s;
      }
    check_text(shape, "filename");
    MeshResource mesh;
    mesh.uri = mesh_uri(shape, filename, mesh.resolved_path);
    mesh.uri_source = at_.at(shape, "filename");
    return Geometry(HeapValue<MeshResource>(std::move(mesh)));
  }
  // Not URDF 1.0, but urdfdom-based tools (Drake, Gazebo's parser) read it: a Z-axis capsule
  // whose length is the cylindrical part.
  if (named(shape, "capsule")) {
    if (choreonoid())
      refused(at_.at(shape), "<capsule> (not URDF 1.0; read as Drake and sdformat read it)");
    else
      convention(at_.at(shape),
                 "<capsule> is not URDF 1.0 (urdfdom refuses it); read as Drake and sdformat read it, a "
                 "capsule along Z whose length is the cylindrical part");
    return along_z(Capsule{});
  }
  report("import-value", at_.at(shape), fmt::format("<{}> is not a URDF geometry", shape->Name()));
  return std::nullopt;
}

void Reader::read_shape(const XMLElement* e, Link& link, bool visual) {
  report_unknown_children(e, {"origin", "geometry", "material"}, visual ? "<visual>" : "<collision>");
  const XMLElement* g = e->FirstChildElement("geometry");
  if (!g) {
    report("import-structure", at_.at(e), fmt::format("this <{}> has no <geometry>", e->Name()));
    return;
  }
  Eigen::Isometry3d X_LS = origin(e);
  Eigen::Vector3d scale(1, 1, 1);
  auto geometry = read_geometry(g, X_LS, scale);
  if (!geometry) return;
  Shape shape;
  if (const char* name = e->Attribute("name")) shape.name = name;
  shape.geometry = std::move(*geometry);
  shape.X_LS = Eigen::AffineCompact3d(X_LS.matrix().topRows<3>());
  if (scale != Eigen::Vector3d(1, 1, 1)) shape.X_LS.linear() = shape.X_LS.linear() * scale.asDiagonal();
  shape.visual = visual;
  shape.collision = !visual;
  shape.source = at_.at(e);
  if (visual) {
    if (const XMLElement* m = e->FirstChildElement("material")) {
      read_material(m, false);
      const char* name = m->Attribute("name");
      if (m->FirstChildElement("color")) {
        // An inline colour applies here even when the name was defined before.
        if (auto rgba = numbers(m->FirstChildElement("color"), "rgba", 4)) {
          Material mat;
          mat.diffuse_color = Eigen::Vector3d((*rgba)[0], (*rgba)[1], (*rgba)[2]);
          mat.transparency = 1.0 - (*rgba)[3];
          shape.appearance.material = mat;
        }
      } else if (name && *name) {
        auto it = materials_.find(name);
        if (it != materials_.end())
          shape.appearance.material = it->second;
        else if (!m->FirstChildElement("texture"))
          report("import-material", at_.at(m, "name"), fmt::format("the material '{}' is not defined", name),
                 "define it at the top level with a <color rgba>");
      }
    }
  }
  link.shapes.push_back(std::move(shape));
}

void Reader::read_link(const XMLElement* e, Link& link) {
  report_unknown_children(e, {"inertial", "visual", "collision"}, "<link>");
  const XMLElement* inertial = e->FirstChildElement("inertial");
  if (inertial) {
    read_inertial(inertial, link);
    if (inertial->NextSiblingElement("inertial"))
      report("import-structure", at_.at(inertial->NextSiblingElement("inertial")),
             "a link has one <inertial>; this one is ignored");
  } else {
    const std::string total = links_without_inertial_ == 1
                                  ? std::string("it is the only such link")
                                  : fmt::format("the {} links without <inertial> add {} kg", links_without_inertial_,
                                                links_without_inertial_);
    if (choreonoid()) {
      // Choreonoid's URDF loader leaves such a link at its Link defaults: 1 kg at the origin with
      // identity inertia. A link without mass contributions is that (body-format-spec §6.4 rule 4),
      // as a .body link without mass data is; the body writer then writes no mass keys either.
      differs(Difference::kMass, at_.at(e),
              fmt::format("link '{}' has no <inertial>: Choreonoid's URDF loader gives it 1 kg at its origin with "
                          "identity inertia (1 kg·m² about each axis), where URDF means a massless frame; {}",
                          link.name, total),
              "give it an <inertial> with its real mass, or load urdf2body's .body of this URDF, which keeps it "
              "massless");
      read_link_shapes(e, link);
      return;
    }
    // URDF: a link without <inertial> has no mass (a frame); Choreonoid's URDF loader gives it 1 kg.
    MassContribution c;
    c.from_link_keys = true;
    c.mass = 0;
    c.source = at_.at(e);
    link.mass_contributions.push_back(c);
    differs(Difference::kMass, at_.at(e),
            fmt::format("link '{}' has no <inertial>: written with mass 0 (URDF's massless frame); Choreonoid's URDF "
                        "loader, and so a wrapper body file around this URDF, gives it 1 kg with identity inertia ({} "
                        "there)",
                        link.name, total));
  }
  read_link_shapes(e, link);
}

void Reader::read_link_shapes(const XMLElement* e, Link& link) {
  for (const XMLElement* v = e->FirstChildElement("visual"); v; v = v->NextSiblingElement("visual"))
    read_shape(v, link, true);
  for (const XMLElement* c = e->FirstChildElement("collision"); c; c = c->NextSiblingElement("collision"))
    read_shape(c, link, false);
}

// Choreonoid's URDF loader reads the <axis> of every joint, a fixed one too: normalised, or 1 0 0
// without one (a zero axis stays zero). It moves nothing, so nothing is reported.
void Reader::read_fixed_axis(const XMLElement* joint, Link& link) {
  link.joint_axis = Eigen::Vector3d::UnitX();
  const XMLElement* a = joint->FirstChildElement("axis");
  if (!a) return;
  link.sources.set(LinkSources::kJointAxis, at_.at(a, "xyz"));
  if (!a->Attribute("xyz")) {
    refused(at_.at(a), "this <axis> has no xyz attribute");
    return;
  }
  if (auto v = vec3(a, "xyz")) link.joint_axis = v->isZero(0) ? *v : v->stableNormalized();
}

void Reader::read_joint(const JointInfo& joint, Link& link, bool collapsed_world) {
  const XMLElement* e = joint.element;
  report_unknown_children(
      e, {"origin", "parent", "child", "axis", "limit", "dynamics", "mimic", "safety_controller", "calibration"},
      "<joint>");
  link.joint_name = joint.name;
  const Eigen::Isometry3d X_PJ = origin(e);
  link.X_PL = Eigen::AffineCompact3d(X_PJ.matrix().topRows<3>());
  if (const XMLElement* o = e->FirstChildElement("origin")) {
    link.sources.set(LinkSources::kTranslation, at_.at(o));
    link.sources.set(LinkSources::kRotation, at_.at(o));
  }
  link.sources.set(LinkSources::kJointType, at_.at(e, "type"));
  const std::string type = e->Attribute("type") ? e->Attribute("type") : "";
  const bool revolute = type == "revolute" || type == "continuous";
  const bool prismatic = type == "prismatic";
  if (revolute)
    link.joint_type = JointType::kRevolute;
  else if (prismatic)
    link.joint_type = JointType::kPrismatic;
  else if (type == "fixed")
    link.joint_type = JointType::kFixed;
  else if (choreonoid() && !type.empty()) {
    // Choreonoid's URDF loader sets a joint type for revolute, continuous, prismatic and fixed
    // only: any other joint keeps its link's default, a fixed joint.
    link.joint_type = JointType::kFixed;
    differs(Difference::kOther, at_.at(e, "type"),
            fmt::format("the {} joint '{}' is a fixed joint in Choreonoid's URDF loader (it reads no other type than "
                        "revolute, continuous, prismatic and fixed): '{}' does not move against '{}'",
                        type, joint.name, joint.child, joint.parent),
            type == "floating" ? "make it the root's joint: a root link is free in Choreonoid" : "");
  } else if (type == "floating")
    link.joint_type = JointType::kFree;
  else if (type == "planar") {
    link.joint_type = JointType::kFixed;
    loss(at_.at(e, "type"), LossKind::kJoints,
         fmt::format("the planar joint '{}' (written as a fixed joint)", joint.name));
  } else {
    report(
        "import-value", at_.at(e, "type"),
        type.empty() ? std::string("this joint has no type attribute") : fmt::format("unknown joint type '{}'", type),
        "revolute, continuous, prismatic, fixed, floating or planar");
  }
  (void)collapsed_world;
  if (choreonoid() && !revolute && !prismatic) read_fixed_axis(e, link);
  if (revolute || prismatic) {
    Eigen::Vector3d axis(1, 0, 0);  // URDF's default
    if (const XMLElement* a = e->FirstChildElement("axis")) {
      link.sources.set(LinkSources::kJointAxis, at_.at(a, "xyz"));
      if (a->Attribute("xyz")) {
        if (auto v = vec3(a, "xyz")) axis = *v;
      } else if (choreonoid()) {
        refused(at_.at(a), "this <axis> has no xyz attribute");
      }
    }
    if (axis.isZero(0)) {
      report("import-value", link.sources.joint_axis().known() ? link.sources.joint_axis() : at_.at(e),
             fmt::format("joint '{}' has a zero axis", joint.name));
    } else {
      // urdfdom normalises; Choreonoid's body loader does not (body-format-spec §4.5). Stable:
      // the norm of "0 0 1e308" overflows to inf.
      axis = axis.stableNormalized();
    }
    link.joint_axis = axis;
    const XMLElement* limit = e->FirstChildElement("limit");
    if (limit) {
      link.sources.set(LinkSources::kJointRange, at_.at(limit));
      // body2urdf writes 1e30 where Choreonoid has no limit (converters/core: numbers.h).
      auto bounded = [](double v) { return std::abs(v) >= converters::kUnlimitedStandIn ? kUnlimited : v; };
      // A revolute bound is written in degrees: one that overflows there cannot be written.
      // (A lower bound at or below -1e30 and an upper one at or above 1e30 mean no limit.)
      auto in_degrees = [&](const char* attribute, double unlimited_side) -> double {
        const double v = number(limit, attribute).value_or(0);
        if (revolute && v * unlimited_side < converters::kUnlimitedStandIn && !std::isfinite(v * 180 / kPi)) {
          report("import-value", at_.at(limit, attribute),
                 fmt::format("{}=\"{}\" is too large to write in degrees", attribute, limit->Attribute(attribute)));
          return 0;
        }
        return v;
      };
      if (type != "continuous") {
        const double lower = limit->Attribute("lower") ? in_degrees("lower", -1) : 0.0;
        const double upper = limit->Attribute("upper") ? in_degrees("upper", 1) : 0.0;
        link.joint_range_lower = lower <= -converters::kUnlimitedStandIn ? -kUnlimited : lower;
        link.joint_range_upper = upper >= converters::kUnlimitedStandIn ? kUnlimited : upper;
        if (lower > upper) report_reversed_range(limit, joint.name, lower, upper);
      }
      if (choreonoid())
        for (const char* attribute : {"velocity", "effort"}) {
          if (!limit->Attribute(attribute))
            refused(at_.at(limit), fmt::format("the <limit> of joint '{}' has no {}", joint.name, attribute));
          else if (number(limit, attribute).value_or(0) < 0)
            refused(at_.at(limit, attribute),
                    fmt::format("the {} limit of joint '{}' is negative", attribute, joint.name));
        }
      if (limit->Attribute("velocity"))
        if (auto v = number(limit, "velocity")) {
          link.sources.set(LinkSources::kJointVelocity, at_.at(limit, "velocity"));
          link.velocity_upper = bounded(std::abs(*v));
          link.velocity_lower = -link.velocity_upper;
        }
      if (limit->Attribute("effort"))
        if (auto v = number(limit, "effort")) {
          link.effort_upper = bounded(std::abs(*v));
          link.effort_lower = -link.effort_upper;
        }
    } else if (type != "continuous") {
      report("import-structure", at_.at(e), fmt::format("the {} joint '{}' has no <limit>", type, joint.name),
             "add <limit lower upper effort velocity> (urdfdom refuses the joint without it)");
    }
  }
  if (const XMLElement* d = e->FirstChildElement("dynamics")) {
    const double damping = d->Attribute("damping") ? number(d, "damping").value_or(0) : 0.0;
    const double friction = d->Attribute("friction") ? number(d, "friction").value_or(0) : 0.0;
    if (damping != 0 || friction != 0)
      loss(at_.at(d), LossKind::kDynamics,
           fmt::format("the damping {} and friction {} of joint '{}'", converters::format_number(damping),
                       converters::format_number(friction), joint.name));
  }
  if (const XMLElement* m = e->FirstChildElement("mimic"))
    loss(at_.at(m), LossKind::kJoints,
         fmt::format("joint '{}' mimicking '{}' (it moves on its own)", joint.name,
                     m->Attribute("joint") ? m->Attribute("joint") : ""));
  if (const XMLElement* s = e->FirstChildElement("safety_controller"))
    loss(at_.at(s), LossKind::kJoints, fmt::format("the safety controller of joint '{}'", joint.name));
  if (const XMLElement* c = e->FirstChildElement("calibration"))
    loss(at_.at(c), LossKind::kJoints, fmt::format("the calibration of joint '{}'", joint.name));
}

// What tinyxml2 takes but XML does not, or reports without a line: UTF-16 text, a NUL byte,
// and character references to what is not an XML character (&#0; would end a name there).
// Comments and CDATA sections are skipped: a reference there is text.
bool Reader::check_document() {
  const SourceLocation start{file_, 1, 1};
  if (text_.empty()) {
    report("import-syntax", start, "the URDF is empty");
    return false;
  }
  if (text_.size() >= 2 && ((text_[0] == '\xFE' && text_[1] == '\xFF') || (text_[0] == '\xFF' && text_[1] == '\xFE'))) {
    report("import-syntax", start, "the URDF is UTF-16 text; a URDF is read as UTF-8",
           "convert it, e.g. with iconv -f UTF-16 -t UTF-8");
    return false;
  }
  int line = 1;
  std::size_t line_start = 0;
  auto here = [&](std::size_t at) { return SourceLocation{file_, line, static_cast<int>(at - line_start) + 1}; };
  for (std::size_t i = 0; i < text_.size(); ++i) {
    const char c = text_[i];
    if (c == '\n') {
      ++line;
      line_start = i + 1;
    } else if (c == '\0') {
      report("import-syntax", here(i), "a NUL byte: a URDF is UTF-8 text (this may be UTF-16)");
      return false;
    } else if (c == '<' && (text_.compare(i, 4, "<!--") == 0 || text_.compare(i, 9, "<![CDATA[") == 0)) {
      const std::size_t end = text_.find(text_[i + 2] == '-' ? "-->" : "]]>", i);
      const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
      for (; i + 1 < stop; ++i)
        if (text_[i + 1] == '\n') {
          ++line;
          line_start = i + 2;
        }
    } else if (c == '&' && i + 1 < text_.size() && text_[i + 1] == '#') {
      const bool hex = i + 2 < text_.size() && text_[i + 2] == 'x';
      std::size_t j = i + (hex ? 3 : 2);
      std::uint64_t code = 0;
      bool digits = false;
      for (; j < text_.size() && std::isxdigit(static_cast<unsigned char>(text_[j])) &&
             (hex || std::isdigit(static_cast<unsigned char>(text_[j])));
           ++j) {
        digits = true;
        const char d = text_[j];
        code = std::min<std::uint64_t>(
            code * (hex ? 16 : 10) + static_cast<std::uint64_t>(
                                         std::isdigit(static_cast<unsigned char>(d)) ? d - '0' : (d | 0x20) - 'a' + 10),
            0x110000);
      }
      if (!digits || j >= text_.size() || text_[j] != ';') continue;  // tinyxml2 reports what is not a reference
      const bool xml_char = code == 0x9 || code == 0xA || code == 0xD || (code >= 0x20 && code <= 0xD7FF) ||
                            (code >= 0xE000 && code <= 0xFFFD) || (code >= 0x10000 && code <= 0x10FFFF);
      if (!xml_char) {
        report("import-syntax", here(i), fmt::format("{} is not a character XML allows", text_.substr(i, j + 1 - i)));
        return false;
      }
    }
  }
  return true;
}

std::optional<Model> Reader::read() {
  if (!check_document()) return std::nullopt;
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text_.data(), text_.size()) != tinyxml2::XML_SUCCESS) {
    // tinyxml2 gives line 0 for what has no line (an empty document).
    const int line = std::max(doc.ErrorLineNum(), 1);
    report("import-syntax", SourceLocation{file_, line, doc.ErrorLineNum() > 0 ? 0 : 1},
           fmt::format("the URDF is not well-formed XML: {}", doc.ErrorStr() ? doc.ErrorStr() : "parse error"));
    return std::nullopt;
  }
  const XMLElement* robot = doc.RootElement();
  if (!robot || !named(robot, "robot")) {
    report("import-syntax", robot ? at_.at(robot) : SourceLocation{file_, 1, 1},
           robot ? fmt::format("the document element is <{}>, not <robot>", robot->Name())
                 : std::string("the document has no element"));
    return std::nullopt;
  }
  if (const XMLElement* second = robot->NextSiblingElement()) {
    report("import-syntax", at_.at(second),
           fmt::format("a second document element <{}> after the <robot>: an XML document has one", second->Name()));
    return std::nullopt;
  }

  Model model;
  model.name = robot->Attribute("name") ? robot->Attribute("name") : "";
  check_text(robot, "name");
  model.source_file = file_;
  model.format_version = 2.0;
  model.source = at_.at(robot);

  const Elements elements = collect(robot);
  for (const XMLElement* link : elements.links) links_without_inertial_ += !link->FirstChildElement("inertial");
  if (elements.links.empty()) {
    report("import-structure", at_.at(robot), "the robot has no links");
    return std::nullopt;
  }
  std::optional<Tree> tree = connect(elements);
  if (!tree) return std::nullopt;
  choose_root(elements, *tree);
  report_cycles(elements, *tree, build_links(elements, *tree, model));
  return model;
}

// Names, materials, what is lost.
Elements Reader::collect(const XMLElement* robot) {
  Elements elements;
  auto& [links, joints, link_index, joint_index] = elements;
  for (const XMLElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (named(e, "link")) {
      const std::string name = required_name(e, "name", "<link>");
      if (name.empty()) continue;
      if (!link_index.emplace(name, links.size()).second) {
        report("import-structure", at_.at(e, "name"),
               fmt::format("a second link named '{}' (the first is at line {})", name,
                           links[link_index[name]]->GetLineNum()));
        continue;
      }
      links.push_back(e);
    } else if (named(e, "joint")) {
      JointInfo j;
      j.element = e;
      j.name = required_name(e, "name", "<joint>");
      const XMLElement* parent = e->FirstChildElement("parent");
      const XMLElement* child = e->FirstChildElement("child");
      if (!parent || !child) {
        report("import-structure", at_.at(e),
               fmt::format("joint '{}' has no <{}>", j.name, parent ? "child" : "parent"));
        continue;
      }
      j.parent = required_name(parent, "link", "<parent>");
      j.child = required_name(child, "link", "<child>");
      if (j.name.empty() || j.parent.empty() || j.child.empty()) continue;
      if (!joint_index.emplace(j.name, joints.size()).second) {
        report("import-structure", at_.at(e, "name"),
               fmt::format("a second joint named '{}' (the first is at line {})", j.name,
                           joints[joint_index[j.name]].element->GetLineNum()));
        continue;
      }
      joints.push_back(j);
    } else if (named(e, "material")) {
      read_material(e, true);
    } else if (named(e, "transmission")) {
      loss(at_.at(e), LossKind::kDynamics,
           fmt::format("the transmission '{}'", e->Attribute("name") ? e->Attribute("name") : ""));
    } else if (named(e, "gazebo")) {
      loss(at_.at(e), LossKind::kDynamics,
           fmt::format("the <gazebo> extension{}",
                       e->Attribute("reference") ? fmt::format(" for '{}'", e->Attribute("reference")) : ""));
    } else if (!named(e, "mujoco")) {  // MuJoCo's compiler hints (body2urdf writes them): nothing of the robot
      report("import-unknown-element", at_.at(e),
             fmt::format("<{}> in a <robot> is not URDF; it is ignored", e->Name()));
    }
  }
  if (choreonoid()) collect_visual_materials(elements);
  return elements;
}

// Choreonoid's URDF loader knows every material before it reads a link: the top-level ones, then
// those its visuals define, in document order, the first of a name winning. A visual may so name
// a colour that a later link defines. (Each is reported where it is read, not here.)
void Reader::collect_visual_materials(const Elements& elements) {
  for (const XMLElement* link : elements.links)
    for (const XMLElement* v = link->FirstChildElement("visual"); v; v = v->NextSiblingElement("visual")) {
      const XMLElement* m = v->FirstChildElement("material");
      const XMLElement* color = m ? m->FirstChildElement("color") : nullptr;
      const char* name = m ? m->Attribute("name") : nullptr;
      const char* rgba = color ? color->Attribute("rgba") : nullptr;
      if (!name || !*name || !rgba) continue;
      if (auto v4 = comma_separated(rgba, 4)) {
        Material material;
        material.diffuse_color = Eigen::Vector3d((*v4)[0], (*v4)[1], (*v4)[2]);
        material.transparency = 1.0 - (*v4)[3];
        materials_.emplace(name, material);
      }
    }
}

// Each link has at most one parent joint; a link without one is a root.
std::optional<Tree> Reader::connect(const Elements& elements) {
  const auto& [links, joints, link_index, joint_index] = elements;
  Tree tree;
  auto& parent_joint = tree.parent_joint;
  auto& child_joints = tree.child_joints;
  auto& roots = tree.roots;
  parent_joint.assign(links.size(), -1);
  child_joints.resize(links.size());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const JointInfo& joint = joints[j];
    auto parent = link_index.find(joint.parent);
    auto child = link_index.find(joint.child);
    bool ok = true;
    for (auto [found, end, which] :
         {std::tuple(parent, link_index.end(), "parent"), std::tuple(child, link_index.end(), "child")}) {
      if (found == end) {
        const XMLElement* ref = joint.element->FirstChildElement(which);
        report("import-structure", at_.at(ref, "link"),
               fmt::format("joint '{}' names the {} link '{}', which is not defined", joint.name, which,
                           std::strcmp(which, "parent") == 0 ? joint.parent : joint.child));
        ok = false;
      }
    }
    if (!ok) continue;
    if (parent->second == child->second) {
      report("import-structure", at_.at(joint.element->FirstChildElement("child"), "link"),
             fmt::format("joint '{}' joins link '{}' to itself", joint.name, joint.child));
      continue;
    }
    int& existing = parent_joint[child->second];
    if (existing >= 0) {
      report("import-structure", at_.at(joint.element->FirstChildElement("child"), "link"),
             fmt::format("link '{}' is the child of a second joint '{}' (the first is '{}' at line {})", joint.child,
                         joint.name, joints[static_cast<std::size_t>(existing)].name,
                         joints[static_cast<std::size_t>(existing)].element->GetLineNum()));
      continue;
    }
    existing = static_cast<int>(j);
    child_joints[parent->second].push_back(static_cast<int>(j));
  }
  for (std::size_t i = 0; i < links.size(); ++i)
    if (parent_joint[i] < 0) roots.push_back(i);
  if (roots.empty()) {
    const JointInfo& j = joints[static_cast<std::size_t>(parent_joint[0])];
    report("import-structure", at_.at(j.element),
           fmt::format("the links form a cycle: every link is the child of a joint (joint '{}' closes one)", j.name));
    return std::nullopt;
  }
  for (std::size_t r = 1; r < roots.size(); ++r)
    report("import-structure", at_.at(links[roots[r]], "name"),
           fmt::format("link '{}' is a second root (no joint has it as child; the first root is '{}' at line {})",
                       links[roots[r]]->Attribute("name"), links[roots[0]]->Attribute("name"),
                       links[roots[0]]->GetLineNum()),
           "join it to the tree with a joint");

  tree.root = roots[0];
  return tree;
}

// A root named "world" with one fixed or floating joint is the convention for fixing (or
// freeing) the base in the world: the child becomes the root with that joint's type, name and
// pose (the form body2urdf writes back); what the world link holds is reported lost. A world
// on a planar joint, or with several children, stays a link (the body cannot fix its root to
// a plane or several bodies to the world).
void Reader::choose_root(const Elements& elements, Tree& tree) {
  const XMLElement* r = elements.links[tree.root];
  const std::vector<int>& children = tree.child_joints[tree.root];
  if (std::strcmp(r->Attribute("name"), "world") != 0 || children.size() != 1) return;
  const JointInfo& j = elements.joints[static_cast<std::size_t>(children[0])];
  const char* type = j.element->Attribute("type");
  if (!type || (std::strcmp(type, "fixed") != 0 && std::strcmp(type, "floating") != 0)) return;
  // Choreonoid's URDF loader has no such convention: every link is a link, and the one without
  // a parent joint is the body's root, on a free joint.
  const bool has_inertial = r->FirstChildElement("inertial") != nullptr;
  if (choreonoid()) {
    const bool fixed = std::strcmp(type, "fixed") == 0;
    differs(Difference::kWorld, at_.at(r, "name"),
            fmt::format("the root link 'world' stays a link in Choreonoid's URDF loader: the free-floating root of the "
                        "body ({}), holding '{}' on the fixed joint '{}'; {}",
                        has_inertial ? "with its <inertial>" : "1 kg with identity inertia: it has no <inertial>",
                        j.child, j.name,
                        fixed ? "the robot is not fixed to the ground, where ROS tools take 'world' as the fixed frame"
                              : "the robot carries the 'world' link"),
            fmt::format("load urdf2body's .body of this URDF instead: its root is '{}' on a {} joint, without 'world'",
                        j.child, fixed ? "fixed" : "free"));
    return;
  }
  tree.root_joint = children[0];
  tree.root = elements.link_index.at(j.child);
  report_world_content(r);
  differs(Difference::kWorld, at_.at(r, "name"),
          fmt::format("the root link 'world' is the fixed frame: '{}' is written as the root on a {} joint (as ROS "
                      "tools read 'world'); Choreonoid's URDF loader, and so a wrapper body file around this URDF, "
                      "keeps 'world' as the free-floating root link{}, so that the robot is not fixed there",
                      j.child, std::strcmp(type, "fixed") == 0 ? "fixed" : "free",
                      has_inertial ? "" : " (of 1 kg: it has no <inertial>)"));
}

// Depth-first pre-order from the root, children in joint document order; joint ids in the
// document order of the movable joints. Returns which links were reached.
std::vector<bool> Reader::build_links(const Elements& elements, const Tree& tree, Model& model) {
  const auto& [links, joints, link_index, joint_index] = elements;
  const auto& parent_joint = tree.parent_joint;
  const auto& child_joints = tree.child_joints;
  const int root_joint = tree.root_joint;
  std::vector<int> joint_id(joints.size(), -1);
  {
    int next = 0;
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const char* type = joints[j].element->Attribute("type");
      if (static_cast<int>(j) == root_joint || !type) continue;
      if (!std::strcmp(type, "revolute") || !std::strcmp(type, "continuous") || !std::strcmp(type, "prismatic"))
        joint_id[j] = next++;
    }
  }

  std::vector<bool> visited(links.size(), false);
  std::vector<std::pair<std::size_t, LinkIndex>> stack{{tree.root, -1}};
  model.links.reserve(links.size());
  while (!stack.empty()) {
    auto [i, parent] = stack.back();
    stack.pop_back();
    visited[i] = true;
    const XMLElement* e = links[i];
    model.links.emplace_back();
    const LinkIndex index = static_cast<LinkIndex>(model.links.size()) - 1;
    Link& link = model.links.back();
    link.name = e->Attribute("name");
    link.source = at_.at(e);
    link.sources.set(LinkSources::kName, at_.at(e, "name"));
    link.parent = parent;
    if (parent >= 0) {
      const JointInfo& joint = joints[static_cast<std::size_t>(parent_joint[i])];
      link.sources.set(LinkSources::kParent, at_.at(joint.element->FirstChildElement("parent"), "link"));
      read_joint(joint, link, false);
      link.joint_id = joint_id[static_cast<std::size_t>(parent_joint[i])];
      if (link.joint_id >= 0) link.sources.set(LinkSources::kJointId, at_.at(joint.element));
      model.links[static_cast<std::size_t>(parent)].children.push_back(index);
    } else if (root_joint >= 0) {
      read_joint(joints[static_cast<std::size_t>(root_joint)], link, true);
    } else {
      link.joint_type = JointType::kFree;  // URDF's root is not attached to anything
    }
    read_link(e, model.links[static_cast<std::size_t>(index)]);
    const std::vector<int>& children = child_joints[i];
    for (auto it = children.rbegin(); it != children.rend(); ++it)
      stack.emplace_back(link_index.at(joints[static_cast<std::size_t>(*it)].child), index);
  }
  return visited;
}

// Links a joint hangs from the tree but that the walk from the root did not reach hang from a cycle.
void Reader::report_cycles(const Elements& elements, const Tree& tree, const std::vector<bool>& visited) {
  const auto& [links, joints, link_index, joint_index] = elements;
  const auto& parent_joint = tree.parent_joint;
  const auto& roots = tree.roots;
  const int root_joint = tree.root_joint;
  // Whether each link's chain of parents ends at a root (a second one: the first was walked)
  // or runs into a cycle; each link is decided once, so a cycle of n links costs n steps.
  enum class Ends : char { kUnknown, kOnPath, kAtRoot, kInCycle };
  std::vector<Ends> ends(links.size(), Ends::kUnknown);
  auto parent_of = [&elements, &parent_joint](std::size_t i) {
    return elements.link_index.at(elements.joints[static_cast<std::size_t>(parent_joint[i])].parent);
  };
  std::vector<std::size_t> path;
  for (std::size_t i = 0; i < links.size(); ++i) {
    std::size_t at = i;
    while (ends[at] == Ends::kUnknown && parent_joint[at] >= 0) {
      ends[at] = Ends::kOnPath;
      path.push_back(at);
      at = parent_of(at);
    }
    const Ends end = ends[at] == Ends::kUnknown ? Ends::kAtRoot : ends[at] == Ends::kOnPath ? Ends::kInCycle : ends[at];
    if (ends[at] == Ends::kUnknown) ends[at] = Ends::kAtRoot;
    for (std::size_t p : path) ends[p] = end;
    path.clear();
  }
  std::vector<std::string> cycle;
  for (std::size_t i = 0; i < links.size(); ++i)
    // Unreached links with a parent joint: they hang from a cycle (or from a second root).
    if (!visited[i] && parent_joint[i] >= 0 && !(i == roots[0] && root_joint >= 0) && ends[i] == Ends::kInCycle)
      cycle.push_back(links[i]->Attribute("name"));
  if (!cycle.empty()) {
    std::string names;
    for (const std::string& n : cycle) names += (names.empty() ? "'" : ", '") + n + "'";
    const std::size_t first = link_index.at(cycle.front());
    const JointInfo& j = joints[static_cast<std::size_t>(parent_joint[first])];
    report("import-structure", at_.at(j.element),
           fmt::format("the joints form a cycle through the links {} (joint '{}' is on it)", names, j.name));
  }
}

}  // namespace

std::optional<Model> import_urdf(std::string_view text, const std::string& file_name, const UrdfImportOptions& options,
                                 DiagnosticSink& sink) {
  try {
    return Reader(text, file_name, options, sink).read();
  } catch (const std::exception& e) {
    report_rule(sink, "internal-error", SourceLocation{file_name, 0, 0}, e.what());
    return std::nullopt;
  }
}

}  // namespace bodyfmt::urdf_import
