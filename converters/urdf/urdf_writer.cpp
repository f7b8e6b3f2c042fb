#include "urdf_writer.h"

#include "ros_package.h"
#include "xml_string_printer.h"

#include <bodyfmt/converters/loss.h>
#include <bodyfmt/converters/names.h>
#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/converters/preflight.h>
#include <bodyfmt/converters/staged_files.h>
#include <bodyfmt/converters/transforms.h>
#include <bodyfmt/inertia.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/tessellate.h>

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

namespace bodyfmt::urdf {
namespace {

namespace fs = std::filesystem;

/// A binary STL is 84 bytes of header and count, then 50 bytes per triangle; an ASCII STL
/// (which starts with "solid", as some binary headers do too) does not add up to that.
bool is_binary_stl(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  unsigned char head[84] = {};
  if (ec || size < 84 || !in.read(reinterpret_cast<char*>(head), 84)) return false;
  const std::uintmax_t n =
      head[80] | (head[81] << 8) | (head[82] << 16) | (static_cast<std::uintmax_t>(head[83]) << 24);
  return size == 84 + 50 * n;
}

using converters::format_number;
using converters::format_vector;
using tinyxml2::XMLElement;

constexpr std::string_view kTarget = "URDF";

using converters::decompose;
using converters::finite_or_stand_in;
using converters::nearly_equal;
using converters::rpy_of;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// One <visual>/<collision> body: origin, a geometry filler and an optional colour.
struct Piece {
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  std::function<void(XMLElement*)> geometry;
  std::optional<Material> material;
};

class Writer {
 public:
  Writer(const Model& model, const Derived& derived, const UrdfOptions& options, converters::OutputSet& output,
         DiagnosticSink& sink)
      : model_(model), derived_(derived), options_(options), output_(output), sink_(sink) {}

  bool run();

 private:
  XMLElement* element(XMLElement* parent, const char* name) {
    XMLElement* e = doc_.NewElement(name);
    parent->InsertEndChild(e);
    return e;
  }
  void comment(XMLElement* parent, const std::string& text) {
    parent->InsertEndChild(doc_.NewComment((" " + converters::xml_comment_text(text) + " ").c_str()));
  }
  void loss(converters::LossKind kind, XMLElement* parent, const SourceLocation& at, const std::string& what,
            const std::string& hint = {}) {
    converters::report_loss(sink_, at, kTarget, kind, what, hint);
    comment(parent, "export-loss: " + what);
  }
  /// Reports a rule whose table severity is fatal and marks the export failed.
  void fatal(std::string_view rule, const SourceLocation& at, std::string message) {
    report_rule(sink_, rule, at, std::move(message));
    failed_ = true;
  }
  /// Reports names URDF tools cannot use; fails on names XML cannot hold.
  void check_name(const std::string& name, const char* what, const SourceLocation& at);
  void origin(XMLElement* parent, const Eigen::Affine3d& X, bool always = false);
  void write_inertial(XMLElement* link_el, std::size_t index);
  void write_shapes(XMLElement* link_el, std::size_t link_index);
  std::vector<Piece> pieces(XMLElement* link_el, const Link& link, std::size_t link_index, std::size_t shape_index,
                            const Shape& shape);
  void add_mesh_pieces(std::vector<Piece>& out, const std::string& key, const std::string& stem,
                       const TriangleMesh& mesh, const Eigen::Affine3d& X_LS, const std::optional<Material>& material,
                       double extra_scale = 1.0);
  std::string stage_mesh(const std::string& key, const std::string& stem, const TriangleMesh& mesh,
                         const std::optional<Material>& material);
  std::string stage_file_copy(const std::string& source_path);
  std::string uri(const std::string& relative) const {
    if (options_.package_uri.empty()) return relative;
    if (options_.package_root.empty()) return options_.package_uri + relative;
    std::error_code ec;
    // Staged paths stay inside the package (OutputSet::allow_root), so this always has a value.
    return options_.package_uri +
           path_in_package(options_.package_root, fs::absolute(output_.directory(), ec) / relative).value_or(relative);
  }
  std::string material_name(const Material& material);
  void write_joint(std::size_t index, const std::string& joint_name);
  void write_devices(XMLElement* link_el, std::size_t link_index);
  /// Prints the children of robot_ built so far and deletes them, so that the document never
  /// holds more than the element being written (a 100k-link robot would take ~4.5 KB a link).
  void flush();
  void write_mesh_geometry(XMLElement* g, const std::string& filename, const Eigen::Vector3d& scale) {
    XMLElement* m = element(g, "mesh");
    m->SetAttribute("filename", filename.c_str());
    if (!(scale.array() == 1.0).all()) m->SetAttribute("scale", format_vector(scale).c_str());
  }

  const Model& model_;
  const Derived& derived_;
  const UrdfOptions& options_;
  converters::OutputSet& output_;
  DiagnosticSink& sink_;
  tinyxml2::XMLDocument doc_;
  /// Holds the children of <robot> until flush() prints them; its own tags are printed apart.
  XMLElement* robot_ = nullptr;
  std::string text_;  // the URDF file, printed as it is built
  XmlStringPrinter printer_{text_};
  std::size_t materials_at_ = 0;  // where in text_ the named materials go
  bool failed_ = false;
  std::vector<std::pair<std::string, std::string>> materials_;  // name, rgba; first-use order
  std::map<std::string, std::string> material_by_rgba_;
  const std::string mesh_folder_ = converters::generated_folder(options_.mesh_folder, "meshes", output_, model_.name);
  converters::StagedFiles staged_{output_, mesh_folder_};
  std::set<std::string> link_names_;
  std::vector<XMLElement*> pending_joints_;
};

void Writer::flush() {
  for (const tinyxml2::XMLNode* child = robot_->FirstChild(); child; child = child->NextSibling())
    child->Accept(&printer_);
  robot_->DeleteChildren();
}

void Writer::check_name(const std::string& name, const char* what, const SourceLocation& at) {
  if (!converters::is_xml_text(name)) {
    fatal("export-xml-text", at,
          fmt::format("{} name cannot be written in XML (control characters or invalid UTF-8)", what));
    return;
  }
  const std::string problem = converters::urdf_name_problem(name);
  if (!problem.empty()) {
    report_rule(sink_, "export-name", at,
                fmt::format("{} name \"{}\" is not a valid URDF name: {}", what, name, problem),
                "use letters, digits and '_' (ROS tools such as tf and MoveIt rely on it)");
  }
}

void Writer::origin(XMLElement* parent, const Eigen::Affine3d& X, bool always) {
  const Eigen::Vector3d xyz = X.translation();
  const bool rotated = !X.linear().isIdentity(0);
  if (!always && !rotated && xyz.isZero(0)) return;
  XMLElement* o = element(parent, "origin");
  o->SetAttribute("xyz", format_vector(xyz).c_str());
  o->SetAttribute("rpy", format_vector(rotated ? rpy_of(X.linear()) : Eigen::Vector3d::Zero()).c_str());
}

void Writer::write_inertial(XMLElement* link_el, std::size_t index) {
  const MassProperties& mp = derived_.mass[index];
  XMLElement* inertial = element(link_el, "inertial");
  // body-format-spec §6.4/§19: the CoM frame has the link's axes, so rpy stays 0 and the
  // tensor is written as it is (symmetrised); defaults (1 kg, identity) are written too.
  origin(inertial, Eigen::Isometry3d(Eigen::Translation3d(mp.center_of_mass)), true);
  element(inertial, "mass")->SetAttribute("value", format_number(mp.mass).c_str());
  const Eigen::Matrix3d I = symmetrized_inertia(mp.inertia);
  XMLElement* in = element(inertial, "inertia");
  in->SetAttribute("ixx", format_number(I(0, 0)).c_str());
  in->SetAttribute("ixy", format_number(I(0, 1)).c_str());
  in->SetAttribute("ixz", format_number(I(0, 2)).c_str());
  in->SetAttribute("iyy", format_number(I(1, 1)).c_str());
  in->SetAttribute("iyz", format_number(I(1, 2)).c_str());
  in->SetAttribute("izz", format_number(I(2, 2)).c_str());
}

std::string Writer::material_name(const Material& material) {
  // Colours are fractions (appearance-value-range reports others): written clamped.
  const Eigen::Vector4d rgba = Eigen::Vector4d(material.diffuse_color.x(), material.diffuse_color.y(),
                                               material.diffuse_color.z(), 1.0 - material.transparency)
                                   .cwiseMax(0.0)
                                   .cwiseMin(1.0);
  const std::string key = format_vector(rgba);
  auto it = material_by_rgba_.find(key);
  if (it != material_by_rgba_.end()) return it->second;
  std::string name = fmt::format("material_{}", materials_.size());
  materials_.emplace_back(name, key);
  material_by_rgba_.emplace(key, name);
  return name;
}

std::string Writer::stage_mesh(const std::string& key, const std::string& stem, const TriangleMesh& mesh,
                               const std::optional<Material>& material) {
  std::string error;
  std::optional<std::string> relative = staged_.mesh(key, stem, mesh, material, options_.mesh_format, error);
  if (!relative) fatal("export-write", model_.source, error);
  return relative.value_or(std::string());
}

std::string Writer::stage_file_copy(const std::string& source_path) {
  std::string error;
  std::optional<std::string> relative = staged_.copy(source_path, error);
  if (!relative) fatal("export-write", model_.source, error);
  return relative.value_or(std::string());
}

void Writer::add_mesh_pieces(std::vector<Piece>& out, const std::string& key, const std::string& stem,
                             const TriangleMesh& mesh, const Eigen::Affine3d& X_LS,
                             const std::optional<Material>& material, double extra_scale) {
  Piece piece;
  piece.material = material;
  if (auto sr = decompose(X_LS.linear())) {
    // Rigid placement plus a per-axis scale: the mesh file is shared, <mesh scale> scales it.
    piece.origin.linear() = sr->rotation;
    piece.origin.translation() = X_LS.translation();
    const std::string relative = stage_mesh(key, stem, mesh, material);
    const Eigen::Vector3d scale = sr->scale * extra_scale;
    piece.geometry = [this, relative, scale](XMLElement* g) { write_mesh_geometry(g, uri(relative), scale); };
  } else {
    // Shear or mirror: bake the linear part into the vertices (mirrors flip the winding back).
    TriangleMesh baked = mesh;
    const Eigen::Matrix3d L = X_LS.linear() * extra_scale;
    for (auto& v : baked.vertices) v = L * v;
    baked.normals.clear();
    if (L.determinant() < 0) {
      for (auto& t : baked.triangles) std::swap(t[1], t[2]);
    }
    piece.origin.translation() = X_LS.translation();
    const std::string relative = stage_mesh(key + ":baked", stem, baked, material);
    piece.geometry = [this, relative](XMLElement* g) {
      write_mesh_geometry(g, uri(relative), Eigen::Vector3d::Ones());
    };
  }
  out.push_back(std::move(piece));
}

std::vector<Piece> Writer::pieces(XMLElement* link_el, const Link& link, std::size_t link_index,
                                  std::size_t shape_index, const Shape& shape) {
  std::vector<Piece> out;
  const std::optional<Material>& material = shape.appearance.material;
  const std::string shape_key = fmt::format("shape:{}:{}", link_index, shape_index);
  const std::string stem =
      fmt::format("{}_{}", link.name, shape.name.empty() ? fmt::format("shape{}", shape_index) : shape.name.str());
  const auto sr = decompose(shape.X_LS.linear());
  auto tessellated = [&](bool report_scale) {
    if (report_scale) {
      loss(converters::LossKind::kGeometry, link_el, shape.source,
           fmt::format("a non-uniformly scaled {} as a primitive", geometry_type_name(shape.geometry)),
           "written as a tessellated mesh");
    }
    GeometryAlreadyReported filtered(sink_);
    TriangleMesh mesh = compute_shape_local_mesh(model_, shape, filtered);
    if (mesh.empty()) {
      loss(converters::LossKind::kGeometry, link_el, shape.source,
           fmt::format("an empty {} (nothing to draw)", geometry_type_name(shape.geometry)));
      return;
    }
    add_mesh_pieces(out, shape_key, stem, mesh, shape.X_LS, material);
  };
  auto primitive = [&](std::function<void(XMLElement*)> fill, const Eigen::Matrix3d& extra_rotation) {
    Piece piece;
    piece.origin.linear() = sr->rotation * extra_rotation;
    piece.origin.translation() = shape.X_LS.translation();
    piece.geometry = std::move(fill);
    piece.material = material;
    out.push_back(std::move(piece));
  };

  if (const auto* box = std::get_if<Box>(&shape.geometry); box && sr) {
    const Eigen::Vector3d size = box->size.cwiseProduct(sr->scale);
    primitive([this, size](XMLElement* g) { element(g, "box")->SetAttribute("size", format_vector(size).c_str()); },
              Eigen::Matrix3d::Identity());
  } else if (const auto* sphere = std::get_if<Sphere>(&shape.geometry)) {
    if (sr && nearly_equal(sr->scale.x(), sr->scale.y()) && nearly_equal(sr->scale.x(), sr->scale.z())) {
      const double r = sphere->radius * sr->scale.x();
      primitive([this, r](XMLElement* g) { element(g, "sphere")->SetAttribute("radius", format_number(r).c_str()); },
                Eigen::Matrix3d::Identity());
    } else {
      tessellated(true);
    }
  } else if (const auto* cyl = std::get_if<Cylinder>(&shape.geometry)) {
    if (sr && nearly_equal(sr->scale.x(), sr->scale.z())) {
      if (!cyl->top || !cyl->bottom) {
        loss(converters::LossKind::kGeometry, link_el, shape.source, "a cylinder without its top or bottom cap",
             "URDF cylinders are closed");
      }
      const double r = cyl->radius * sr->scale.x();
      const double h = cyl->height * sr->scale.y();
      // body-format-spec §19: a Body cylinder runs along +Y, a URDF cylinder along +Z.
      // Rx(-90°) maps +Z onto +Y exactly (Choreonoid's importer uses +90°; the shape is symmetric).
      primitive(
          [this, r, h](XMLElement* g) {
            XMLElement* c = element(g, "cylinder");
            c->SetAttribute("radius", format_number(r).c_str());
            c->SetAttribute("length", format_number(h).c_str());
          },
          Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix());
    } else {
      tessellated(true);
    }
  } else if (const auto* res = geometry_if<MeshResource>(shape.geometry)) {
    if (res->mesh < 0 || static_cast<std::size_t>(res->mesh) >= model_.meshes.size() ||
        model_.meshes[static_cast<std::size_t>(res->mesh)].parts.empty()) {
      loss(converters::LossKind::kGeometry, link_el, shape.source,
           fmt::format("mesh '{}', which could not be loaded; the shape is left out", res->uri));
      return out;
    }
    const MeshAsset& asset = model_.meshes[static_cast<std::size_t>(res->mesh)];
    const std::string ext = lower_extension(res->resolved_path);
    const bool usable_as_is = (ext == ".stl" || ext == ".dae" || ext == ".obj") && res->node.empty() && !res->y_up &&
                              !res->resolved_path.empty();
    const bool copy = options_.copy_meshes || !options_.package_uri.empty();
    bool textured = false;
    for (const MeshPart& part : asset.parts) textured = textured || part.texture.has_value();
    if (textured)
      loss(converters::LossKind::kTextures, link_el, shape.source, fmt::format("the texture of mesh '{}'", res->uri),
           "colours are kept");
    // A copy is a file the user asked for in --mesh-format: one in another format is converted,
    // and so is an ASCII STL (MuJoCo reads binary STL only).
    const bool in_wanted_format = ext == "." + std::string(converters::mesh_format_extension(options_.mesh_format)) &&
                                  (ext != ".stl" || is_binary_stl(res->resolved_path));
    if (usable_as_is && sr && (!copy || in_wanted_format)) {
      std::string target;
      if (copy) {
        target = uri(stage_file_copy(res->resolved_path));
      } else {
        std::error_code ec;
        target = fs::relative(fs::absolute(res->resolved_path, ec), fs::absolute(output_.directory(), ec), ec)
                     .generic_string();
        if (target.empty()) target = fs::absolute(res->resolved_path, ec).generic_string();
      }
      Piece piece;
      piece.origin.linear() = sr->rotation;
      piece.origin.translation() = shape.X_LS.translation();
      const Eigen::Vector3d scale = sr->scale * res->length_scale;
      piece.geometry = [this, target, scale](XMLElement* g) { write_mesh_geometry(g, target, scale); };
      piece.material = material;
      out.push_back(std::move(piece));
    } else {
      // Converted: one mesh file per part, so that each keeps its own colour.
      const std::string asset_stem =
          fs::path(asset.path).stem().string() + (asset.node.empty() ? "" : "_" + asset.node);
      for (std::size_t p = 0; p < asset.parts.size(); ++p) {
        const MeshPart& part = asset.parts[p];
        if (part.mesh.empty()) continue;
        const std::string key = fmt::format("asset:{}:{}", res->mesh, p);
        const std::string part_stem = asset.parts.size() > 1 ? fmt::format("{}_{}", asset_stem, p) : asset_stem;
        add_mesh_pieces(out, sr ? key : key + ":" + shape_key, part_stem, part.mesh, shape.X_LS,
                        material ? material : part.material);
      }
    }
  } else {
    tessellated(false);
  }
  return out;
}

void Writer::write_shapes(XMLElement* link_el, std::size_t link_index) {
  const Link& link = model_.links[link_index];
  std::vector<std::pair<XMLElement*, Piece>> collisions;
  for (std::size_t s = 0; s < link.shapes.size(); ++s) {
    const Shape& shape = link.shapes[s];
    if (shape.appearance.texture) {
      loss(converters::LossKind::kTextures, link_el, shape.source,
           fmt::format("the texture '{}'", shape.appearance.texture->uri), "colours are kept");
    }
    if (shape.appearance.material && !shape.appearance.material->emissive_color.isZero(0)) {
      loss(converters::LossKind::kMaterials, link_el, shape.source, "an emissive colour",
           "URDF materials have one rgba colour");
    }
    if (!shape.visual && !shape.collision) continue;
    for (Piece& piece : pieces(link_el, link, link_index, s, shape)) {
      // Body-format-spec §7.3: a shape under Visual is visual only, under Collision collision
      // only, under neither both.
      for (const char* kind : {"visual", "collision"}) {
        const bool wanted = kind[0] == 'v' ? shape.visual : shape.collision;
        if (!wanted) continue;
        XMLElement* e = element(link_el, kind);
        if (!shape.name.empty()) e->SetAttribute("name", shape.name.str().c_str());
        origin(e, piece.origin);
        piece.geometry(element(e, "geometry"));
        if (kind[0] == 'v' && piece.material) {
          element(e, "material")->SetAttribute("name", material_name(*piece.material).c_str());
        }
      }
    }
  }
}

void Writer::write_devices(XMLElement* link_el, std::size_t link_index) {
  for (std::size_t d = 0; d < model_.devices.size(); ++d) {
    const Device& device = model_.devices[d];
    if (device.link != static_cast<LinkIndex>(link_index)) continue;
    const std::string label = device.name.empty() ? device.type : device.name;
    if (!options_.devices_as_frames) {
      loss(converters::LossKind::kDevices, link_el, device.source, fmt::format("device '{}' ({})", label, device.type),
           "--devices-as-frames writes it as a fixed child link");
      continue;
    }
    const Link& link = model_.links[link_index];
    std::string name = device.name.empty() ? fmt::format("{}_{}_{}", link.name, device.type, d) : device.name;
    if (link_names_.count(name)) name = link.name + "_" + name;
    for (int n = 2; link_names_.count(name); ++n) name = fmt::format("{}_{}", name, n);
    check_name(name, "device", device.source);
    link_names_.insert(name);
    comment(robot_, fmt::format("device {} ({}, id {}) on {}", label, device.type, device.id, link.name));
    element(robot_, "link")->SetAttribute("name", name.c_str());
    XMLElement* j = doc_.NewElement("joint");
    j->SetAttribute("name", (name + "_joint").c_str());
    j->SetAttribute("type", "fixed");
    origin(j, device.X_LD);
    element(j, "parent")->SetAttribute("link", link.name.c_str());
    element(j, "child")->SetAttribute("link", name.c_str());
    pending_joints_.push_back(j);
  }
}

void Writer::write_joint(std::size_t index, const std::string& joint_name) {
  const Link& link = model_.links[index];
  const Link& parent = model_.links[static_cast<std::size_t>(link.parent)];
  if (link.joint_id >= 0) comment(robot_, fmt::format("joint_id {}", link.joint_id));
  XMLElement* j = element(robot_, "joint");
  j->SetAttribute("name", joint_name.c_str());
  const char* type = "fixed";
  bool movable = false;
  switch (link.joint_type) {
    case JointType::kRevolute:
      movable = true;
      type = link.joint_range_lower <= -kUnlimited && link.joint_range_upper >= kUnlimited ? "continuous" : "revolute";
      break;
    case JointType::kPrismatic:
      movable = true;
      type = "prismatic";
      break;
    case JointType::kPseudoContinuousTrack:
      comment(j, fmt::format("pseudo_continuous_track axis {}", format_vector(link.joint_axis)));
      loss(converters::LossKind::kTracks, j, source_of(link, LinkSources::kJointType),
           fmt::format("the pseudo_continuous_track of '{}' (a fixed joint is written; axis {})", link.name,
                       format_vector(link.joint_axis)));
      break;
    case JointType::kFree:
      loss(converters::LossKind::kJoints, j, source_of(link, LinkSources::kJointType),
           fmt::format("the free joint of the non-root link '{}' (a fixed joint is written)", link.name));
      break;
    case JointType::kFixed: break;
  }
  j->SetAttribute("type", type);
  origin(j, link.X_PL);
  element(j, "parent")->SetAttribute("link", parent.name.c_str());
  element(j, "child")->SetAttribute("link", link.name.c_str());
  if (!movable) return;
  const double norm = link.joint_axis.norm();
  element(j, "axis")->SetAttribute(
      "xyz", format_vector(norm > 0 ? Eigen::Vector3d(link.joint_axis / norm) : link.joint_axis).c_str());
  // URDF has one symmetric bound for velocity and effort.
  auto symmetric = [&](double lo, double hi, const char* what, const SourceLocation& at) {
    if (lo == -hi) return finite_or_stand_in(hi);
    const double bound = std::min(std::abs(lo), std::abs(hi));
    loss(converters::LossKind::kJoints, j, at.known() ? at : link.source,
         fmt::format("the asymmetric {} range [{}, {}] of '{}' (written as {})", what, format_number(lo),
                     format_number(hi), joint_name, format_number(finite_or_stand_in(bound))));
    return finite_or_stand_in(bound);
  };
  const double velocity =
      symmetric(link.velocity_lower, link.velocity_upper, "velocity", link.sources.joint_velocity());
  const double effort = symmetric(link.effort_lower, link.effort_upper, "effort", link.source);
  XMLElement* limit = element(j, "limit");
  if (std::string_view(type) != "continuous") {
    limit->SetAttribute("lower", format_number(finite_or_stand_in(link.joint_range_lower)).c_str());
    limit->SetAttribute("upper", format_number(finite_or_stand_in(link.joint_range_upper)).c_str());
  }
  limit->SetAttribute("effort", format_number(effort).c_str());
  limit->SetAttribute("velocity", format_number(velocity).c_str());
  if (link.joint_axis_inertia != 0) {
    loss(converters::LossKind::kDynamics, j, link.source,
         fmt::format("the rotor inertia {} of '{}'", format_number(link.joint_axis_inertia), joint_name));
  }
  if (link.initial_displacement != 0) {
    loss(converters::LossKind::kDynamics, j, link.source,
         fmt::format("the initial displacement {} of '{}'", format_number(link.initial_displacement), joint_name));
  }
}

bool Writer::run() {
  if (model_.links.empty() || derived_.mass.size() != model_.links.size()) {
    fatal("internal-error", model_.source, "the model has no links or its derived data is missing");
    output_.fail();
    return false;
  }
  robot_ = doc_.NewElement("robot");
  doc_.InsertEndChild(robot_);
  if (!converters::is_xml_text(model_.name)) {
    fatal("export-xml-text", model_.source,
          "the body name cannot be written in XML (control characters or invalid UTF-8)");
  }
  // The declaration tinyxml2 writes for a document (PushHeader writes a shorter one).
  tinyxml2::XMLDeclaration* declaration = doc_.NewDeclaration();
  declaration->Accept(&printer_);
  doc_.DeleteNode(declaration);
  printer_.OpenElement("robot");
  printer_.PushAttribute("name", model_.name.empty() ? "robot" : model_.name.c_str());
  comment(robot_, fmt::format("Generated by body2urdf from {}", fs::path(model_.source_file).filename().string()));
  if (options_.mujoco_compiler) {
    // MuJoCo's URDF reader strips the folders of mesh paths unless told not to; ROS ignores
    // the element.
    element(element(robot_, "mujoco"), "compiler")->SetAttribute("strippath", "false");
  }
  flush();
  materials_at_ = text_.size();

  for (const Link& link : model_.links) link_names_.insert(link.name);
  const Link& root = model_.root();
  if (options_.floating_base) {
    if (link_names_.count("world")) {
      fatal("export-name-conflict", source_of(root, LinkSources::kName),
            "--floating-base adds a link named 'world', but the model already has one");
    } else {
      element(robot_, "link")->SetAttribute("name", "world");
      comment(robot_, "--floating-base: the root's initial pose from the file");
      XMLElement* j = element(robot_, "joint");
      j->SetAttribute("name", "world_joint");
      j->SetAttribute("type", root.joint_type == JointType::kFree ? "floating" : "fixed");
      origin(j, root.X_PL);
      element(j, "parent")->SetAttribute("link", "world");
      element(j, "child")->SetAttribute("link", root.name.c_str());
    }
  }

  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    const Link& link = model_.links[i];
    check_name(link.name, "link", source_of(link, LinkSources::kName));
    XMLElement* link_el = element(robot_, "link");
    link_el->SetAttribute("name", link.name.c_str());
    if (i == 0 && !options_.floating_base) {
      if (!link.X_PL.isApprox(Eigen::AffineCompact3d::Identity(), 0)) {
        loss(converters::LossKind::kDynamics, link_el, source_of(link, LinkSources::kTranslation),
             "the root link's initial pose", "--floating-base writes it as the origin of a joint to a 'world' link");
      }
      if (link.joint_type != JointType::kFree && link.joint_type != JointType::kFixed) {
        loss(converters::LossKind::kJoints, link_el, link.source,
             fmt::format("a {} joint on the root link", joint_type_name(link.joint_type)));
      }
    }
    write_inertial(link_el, i);
    write_shapes(link_el, i);
    if (!link.contact_material.empty() && link.contact_material != "default") {
      loss(converters::LossKind::kDynamics, link_el, link.source,
           fmt::format("the contact material '{}'", link.contact_material.str()));
    }
    if (!link.actuation_mode.empty() && link.joint_type != JointType::kPseudoContinuousTrack) {
      loss(converters::LossKind::kDynamics, link_el, link.source,
           fmt::format("the actuation mode '{}'", link.actuation_mode.str()));
    }
    write_devices(link_el, i);
    flush();
  }

  // Joints sorted by joint id (Choreonoid's URDF importer numbers joints in document order),
  // then the joints without an id in link order.
  std::vector<std::size_t> order;
  for (std::size_t i = 1; i < model_.links.size(); ++i) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const int ia = model_.links[a].joint_id, ib = model_.links[b].joint_id;
    return (ia >= 0 ? ia : INT32_MAX) < (ib >= 0 ? ib : INT32_MAX);
  });
  std::set<std::string> joint_names;
  for (std::size_t i : order) {
    const Link& link = model_.links[i];
    std::string name = link.joint_name.empty() ? link.name : link.joint_name.str();
    if (joint_names.count(name)) {
      std::string unique = name + "_joint";
      for (int n = 2; joint_names.count(unique); ++n) unique = fmt::format("{}_joint{}", name, n);
      report_rule(sink_, "export-name", link.source,
                  fmt::format("joint name \"{}\" is already used; written as \"{}\"", name, unique));
      name = unique;
    }
    joint_names.insert(name);
    check_name(name, "joint", link.source);
    write_joint(i, name);
    flush();
  }
  for (XMLElement* j : pending_joints_) robot_->InsertEndChild(j);
  for (const ExtraJoint& ej : model_.extra_joints) {
    const std::string l1 = ej.link1 >= 0 ? model_.links[static_cast<std::size_t>(ej.link1)].name : "?";
    const std::string l2 = ej.link2 >= 0 ? model_.links[static_cast<std::size_t>(ej.link2)].name : "?";
    loss(converters::LossKind::kExtraJoints, robot_, ej.source,
         fmt::format("the {} extra joint between '{}' and '{}' (a closed loop)", ej.type, l1, l2));
  }

  flush();

  if (failed_) {
    output_.fail();
    return false;
  }
  // Named materials go first, where every reader finds them before their use. They are known
  // only now: printed apart (at the depth of <robot>'s children) and put in after the header.
  std::string materials_text;
  printer_.redirect(materials_text);
  for (const auto& [name, rgba] : materials_) {
    XMLElement* m = element(robot_, "material");
    m->SetAttribute("name", name.c_str());
    element(m, "color")->SetAttribute("rgba", rgba.c_str());
  }
  flush();
  printer_.redirect(text_);
  printer_.CloseElement();
  text_.insert(materials_at_, materials_text);
  output_.set_main(std::move(text_));
  return true;
}

}  // namespace

bool write_urdf(const Model& model, const Derived& derived, const UrdfOptions& options, converters::OutputSet& output,
                DiagnosticSink& sink) {
  if (!converters::check_joints(model, sink)) {
    output.fail();
    return false;
  }
  Writer writer(model, derived, options, output, sink);
  return writer.run();
}

}  // namespace bodyfmt::urdf
