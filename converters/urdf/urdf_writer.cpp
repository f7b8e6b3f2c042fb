#include "urdf_writer.h"

#include "xml_string_printer.h"

#include <bodyfmt/converters/inertia_report.h>
#include <bodyfmt/converters/loss.h>
#include <bodyfmt/converters/names.h>
#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/converters/preflight.h>
#include <bodyfmt/converters/shape_plan.h>
#include <bodyfmt/converters/staged_files.h>
#include <bodyfmt/converters/transforms.h>
#include <bodyfmt/converters/xml_writer.h>
#include <bodyfmt/inertia.h>
#include <bodyfmt/package_map.h>
#include <bodyfmt/physical.h>
#include <bodyfmt/rules.h>

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

using converters::finite_or_stand_in;
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

class Writer : converters::XmlWriter {
 public:
  /// Prints the URDF as it is built, a link at a time, with the named materials put in last.
  bool run();
  Writer(const Model& model, const Derived& derived, const UrdfOptions& options, converters::OutputSet& output,
         DiagnosticSink& sink)
      : XmlWriter(model, derived, output, kTarget, sink), options_(options) {}

 private:
  /// Reports names URDF tools cannot use; fails on names XML cannot hold.
  void check_name(const std::string& name, const char* what, const SourceLocation& at);
  void origin(XMLElement* parent, const Eigen::Affine3d& X, bool always = false);
  /// Reports the inertias URDF consumers refuse, and with --balance-inertia chooses the
  /// balanced tensors written instead. Returns false when an inertia cannot be written: an
  /// asymmetric tensor (URDF holds six numbers) without --balance-inertia.
  bool assess_inertias();
  void write_inertial(XMLElement* link_el, std::size_t index);
  void write_shapes(XMLElement* link_el, std::size_t link_index);
  std::vector<Piece> pieces(XMLElement* link_el, std::size_t link_index, std::size_t shape_index);
  /// Whether mesh files are copied beside the URDF (--copy-meshes, --package-uri).
  bool copies() const { return options_.copy_meshes || !options_.package_uri.empty(); }
  /// Whether a mesh file is referenced (or copied) as it is rather than converted.
  bool references_as_is(const MeshResource& res) const;
  std::string mesh_file_target(const MeshResource& res);
  std::string stage_mesh(const std::string& key, const std::string& stem, const TriangleMesh& mesh,
                         const std::optional<Material>& material);
  std::string stage_file_copy(const std::string& source_path);
  std::string uri(const std::string& relative) const {
    if (options_.package_uri.empty()) return relative;
    if (options_.package_root.empty()) return options_.package_uri + relative;
    std::error_code ec;
    // Staged paths stay inside the package (OutputSet::allow_root), so this always has a value.
    return options_.package_uri +
           bodyfmt::path_in_package(options_.package_root, fs::absolute(output_.directory(), ec) / relative)
               .value_or(relative);
  }
  std::string material_name(const Material& material);
  void write_joint(std::size_t index, const std::string& joint_name);
  std::string write_world(const Link& root);
  void write_devices(XMLElement* link_el, std::size_t link_index);
  /// Prints the children of robot_ built so far and deletes them, so that the document never
  /// holds more than the element being written (a 100k-link robot would take ~4.5 KB a link).
  void flush();
  void write_mesh_geometry(XMLElement* g, const std::string& filename, const Eigen::Vector3d& scale) {
    XMLElement* m = element(g, "mesh");
    m->SetAttribute("filename", filename.c_str());
    if (!(scale.array() == 1.0).all()) m->SetAttribute("scale", format_vector(scale).c_str());
  }

  const UrdfOptions& options_;
  const converters::ShapeTarget shape_target_{kTarget,
                                              /*capsule=*/options_.capsules,
                                              /*min_box_half_edge=*/0,
                                              /*hull_collision=*/false,
                                              /*emissive_color=*/false,
                                              [this](const MeshResource& res) { return references_as_is(res); }};
  /// Holds the children of <robot> until flush() prints them; its own tags are printed apart.
  XMLElement* robot_ = nullptr;
  std::string text_;  // the URDF file, printed as it is built
  XmlStringPrinter printer_{text_};
  std::size_t materials_at_ = 0;                      // where in text_ the named materials go
  converters::MaterialNames<std::string> materials_;  // by rgba, with it
  const std::string mesh_folder_ = converters::generated_folder(options_.mesh_folder, "meshes", output_, model_.name);
  converters::StagedFiles staged_{output_, mesh_folder_};
  std::set<std::string> link_names_;
  std::vector<XMLElement*> pending_joints_;
  std::map<std::size_t, std::pair<Eigen::Matrix3d, std::string>> balanced_;  // link -> tensor, what changed
  std::map<std::size_t, std::vector<std::string>> asymmetric_notes_;         // link -> its symmetrised tensors
};

}  // namespace

bool write_urdf(const Model& model, const Derived& derived, const UrdfOptions& options, converters::OutputSet& output,
                DiagnosticSink& sink) {
  // A reversed range is written as it is (see write_joint).
  return converters::write_xml<Writer>(model, derived, options, output, sink, kTarget,
                                       /*reversed_range_writable=*/true);
}

void Writer::flush() {
  for (const tinyxml2::XMLNode* child = robot_->FirstChild(); child; child = child->NextSibling())
    child->Accept(&printer_);
  robot_->DeleteChildren();
}

void Writer::check_name(const std::string& name, const char* what, const SourceLocation& at) {
  if (!check_xml_name(name, what, at)) return;
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

bool Writer::assess_inertias() {
  // The consumers that load a URDF for dynamics refuse these tensors: Drake
  // (RotationalInertia::CouldBePhysicallyValid), gz-math (MassMatrix3::IsValid) and MuJoCo's
  // compiler. URDF itself holds any six numbers, so the tensor is written as given unless the
  // user asks for the balanced one. A mass they refuse is written as given too; each is a loss
  // of the dynamics kind, so that --allow-loss dynamics accepts it like the others.
  struct DynamicsLoss : DiagnosticSink {
    DiagnosticSink& inner;
    explicit DynamicsLoss(DiagnosticSink& s) : inner(s) {}
    void report(Diagnostic d) override {
      d.category = std::string(converters::loss_kind_name(converters::LossKind::kDynamics));
      inner.report(std::move(d));
    }
  } dynamics_loss(sink_);
  const std::string_view dynamics = converters::loss_kind_name(converters::LossKind::kDynamics);
  PhysicalOptions gate;
  gate.balance_inertia = options_.balance_inertia;
  const PhysicalVerdict verdict = assess_physical(model_, derived_, gate);
  bool writable = true;
  for (const PhysicalFinding& f : verdict.findings) {
    if (f.defect == PhysicalDefect::kInertiaAsymmetric) {
      // bodycheck's error, at its place: <inertia> holds six numbers, so the tensor the model
      // gives is not the one written; only --balance-inertia writes the symmetric one, said.
      const Link& link = model_.links[static_cast<std::size_t>(f.link)];
      if (options_.balance_inertia) {
        report_physical_as(sink_, "export-value-changed", f,
                           "URDF cannot hold " + converters::symmetrised_inertia_text(link, f));
        asymmetric_notes_[static_cast<std::size_t>(f.link)].push_back("export-value-changed: " +
                                                                      converters::symmetrised_inertia_text(link, f));
      } else {
        writable = false;
        converters::report_asymmetric_inertia_refused(sink_, link, f, "URDF holds a symmetric tensor (six numbers)");
      }
      continue;
    }
    const std::size_t i = static_cast<std::size_t>(f.link);
    const Link& link = model_.links[i];
    if (f.defect == PhysicalDefect::kNegativeMass) {
      report_physical_as(dynamics_loss, "export-loss", f,
                         fmt::format("the mass {} kg of link \"{}\" is written as given, but Drake and gz-math refuse "
                                     "a negative mass and MuJoCo clamps it to 0 (loss kind: {})",
                                     format_number(derived_.mass[i].mass), link.name, dynamics));
      continue;
    }
    if (f.defect == PhysicalDefect::kMovingMassless || f.defect == PhysicalDefect::kMovingBelowMinimum) {
      if (!verdict.links[i].usable) continue;  // reported for its negative mass or moment, as body2mjcf does
      report_physical_as(dynamics_loss, "export-loss", f,
                         fmt::format("the mass {} kg and principal moments {} of moving link \"{}\" are written as "
                                     "given, but MuJoCo refuses a moving body below mjMINVAL = 1e-15 when no fixed "
                                     "child carries mass (loss kind: {})",
                                     format_number(derived_.mass[i].mass),
                                     converters::moments_text(f.principal.moments), link.name, dynamics),
                         "give the link its real mass");
      continue;
    }
    if (f.defect != PhysicalDefect::kNotPositiveDefinite && f.defect != PhysicalDefect::kTriangle) continue;
    if (!f.balanced_by_policy) {
      const std::string hint = converters::nearest_inertia_hint(f);
      report_physical_as(
          dynamics_loss, "export-loss", f,
          fmt::format("principal moments {} of link \"{}\" ({}{}) are written as given, but Drake, "
                      "gz-math and MuJoCo refuse to load this URDF (loss kind: {})",
                      converters::moments_text(f.principal.moments), link.name, converters::inertia_defect_text(f),
                      f.validity.negative_moment ? "" : " < 0", dynamics),
          hint + (hint.empty() ? "" : "; ") + "--balance-inertia writes it");
      continue;
    }
    const Eigen::Matrix3d after = f.balanced_inertia();
    const std::string what =
        converters::balanced_inertia_text(link, f, symmetrized_inertia(derived_.mass[i].inertia), after);
    report_physical_as(sink_, "export-value-changed", f, "Drake, gz-math and MuJoCo cannot accept " + what);
    balanced_.emplace(i, std::make_pair(after, what));
  }
  return writable;
}

void Writer::write_inertial(XMLElement* link_el, std::size_t index) {
  const MassProperties& mp = derived_.mass[index];
  const auto balanced = balanced_.find(index);
  const auto symmetrised = asymmetric_notes_.find(index);
  if (symmetrised != asymmetric_notes_.end())
    for (const std::string& note : symmetrised->second) comment(link_el, note);
  if (balanced != balanced_.end()) comment(link_el, "export-value-changed: " + balanced->second.second);
  XMLElement* inertial = element(link_el, "inertial");
  // body-format-spec §6.4/§19: the CoM frame has the link's axes, so rpy stays 0 and the
  // tensor is written as it is (symmetric within the gate's tolerance, or symmetrised with
  // --balance-inertia and said); defaults (1 kg, identity) are written too.
  origin(inertial, Eigen::Isometry3d(Eigen::Translation3d(mp.center_of_mass)), true);
  element(inertial, "mass")->SetAttribute("value", format_number(mp.mass).c_str());
  const Eigen::Matrix3d I = balanced != balanced_.end() ? balanced->second.first : symmetrized_inertia(mp.inertia);
  XMLElement* in = element(inertial, "inertia");
  in->SetAttribute("ixx", format_number(I(0, 0)).c_str());
  in->SetAttribute("ixy", format_number(I(0, 1)).c_str());
  in->SetAttribute("ixz", format_number(I(0, 2)).c_str());
  in->SetAttribute("iyy", format_number(I(1, 1)).c_str());
  in->SetAttribute("iyz", format_number(I(1, 2)).c_str());
  in->SetAttribute("izz", format_number(I(2, 2)).c_str());
}

std::string Writer::material_name(const Material& material) {
  // A URDF material is one colour: materials of the same colour share a name.
  const std::string rgba = format_vector(converters::clamped_rgba(material));
  return materials_.name(rgba, rgba);
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

bool Writer::references_as_is(const MeshResource& res) const {
  const std::string ext = lower_extension(res.resolved_path);
  const bool usable_as_is =
      (ext == ".stl" || ext == ".dae" || ext == ".obj") && res.node.empty() && !res.y_up && !res.resolved_path.empty();
  // A copy is a file the user asked for in --mesh-format: one in another format is converted,
  // and so is an ASCII STL (MuJoCo reads binary STL only).
  const bool in_wanted_format = ext == "." + std::string(converters::mesh_format_extension(options_.mesh_format)) &&
                                (ext != ".stl" || is_binary_stl(res.resolved_path));
  return usable_as_is && (!copies() || in_wanted_format);
}

std::string Writer::mesh_file_target(const MeshResource& res) {
  if (copies()) return uri(stage_file_copy(res.resolved_path));
  std::error_code ec;
  std::string target =
      fs::relative(fs::absolute(res.resolved_path, ec), fs::absolute(output_.directory(), ec), ec).generic_string();
  if (target.empty()) target = fs::absolute(res.resolved_path, ec).generic_string();
  return target;
}

std::vector<Piece> Writer::pieces(XMLElement* link_el, std::size_t link_index, std::size_t shape_index) {
  converters::ShapePlan plan = converters::plan_shape(model_, link_index, shape_index, shape_target_, sink_);
  for (const converters::PlannedLoss& planned : plan.losses) loss(link_el, planned);
  std::vector<Piece> out;
  for (const converters::PlannedPiece& planned : plan.pieces) {
    Piece piece;
    piece.origin = planned.origin;
    piece.material = planned.material;
    using Kind = converters::PlannedPiece::Kind;
    switch (planned.kind) {
      case Kind::kBox:
        piece.geometry = [this, size = planned.size](XMLElement* g) {
          element(g, "box")->SetAttribute("size", format_vector(size).c_str());
        };
        break;
      case Kind::kSphere:
        piece.geometry = [this, r = planned.radius](XMLElement* g) {
          element(g, "sphere")->SetAttribute("radius", format_number(r).c_str());
        };
        break;
      case Kind::kCylinder:
      case Kind::kCapsule:  // planned only with --capsules, else as a mesh
        piece.geometry = [this, r = planned.radius, h = planned.length,
                          name = planned.kind == Kind::kCapsule ? "capsule" : "cylinder"](XMLElement* g) {
          XMLElement* c = element(g, name);
          c->SetAttribute("radius", format_number(r).c_str());
          c->SetAttribute("length", format_number(h).c_str());
        };
        break;
      case Kind::kMesh: {
        const std::string relative = stage_mesh(planned.key, planned.stem, *planned.mesh, planned.material);
        piece.geometry = [this, relative, scale = planned.scale](XMLElement* g) {
          write_mesh_geometry(g, uri(relative), scale);
        };
        break;
      }
      case Kind::kMeshFile:
        piece.geometry = [this, target = mesh_file_target(*planned.file), scale = planned.scale](XMLElement* g) {
          write_mesh_geometry(g, target, scale);
        };
        break;
    }
    out.push_back(std::move(piece));
  }
  return out;
}

void Writer::write_shapes(XMLElement* link_el, std::size_t link_index) {
  const Link& link = model_.links[link_index];
  std::vector<std::pair<XMLElement*, Piece>> collisions;
  for (std::size_t s = 0; s < link.shapes.size(); ++s) {
    const Shape& shape = link.shapes[s];
    for (Piece& piece : pieces(link_el, link_index, s)) {
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
  const Eigen::Vector3d axis = written_axis(j, index);
  element(j, "axis")->SetAttribute("xyz", format_vector(axis).c_str());
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
    if (link.joint_range_lower > link.joint_range_upper)
      comment(j,
              "lower > upper as in the model (bodycheck: joint-range-reversed): urdfdom keeps it, MuJoCo reads "
              "the joint as unlimited, Drake refuses it");
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

// Choreonoid holds a fixed root where the file places it, but a URDF consumer floats the root
// unless it hangs from a `world` link: a fixed root is always written on a fixed joint to
// `world` at its pose. A free root whose joint has a name of its own came from a `world` link on
// a floating joint (urdf2body keeps the joint's name) and goes back to one; --floating-base
// writes every root so. Returns the name of the joint written ("" when none is).
std::string Writer::write_world(const Link& root) {
  const bool named_joint = !root.joint_name.empty() && root.joint_name != root.name;
  const bool wanted = options_.floating_base || root.joint_type == JointType::kFixed ||
                      (root.joint_type == JointType::kFree && named_joint);
  if (!wanted) return {};
  if (link_names_.count("world")) {
    if (options_.floating_base)
      fatal("export-name-conflict", source_of(root, LinkSources::kName),
            "--floating-base adds a link named 'world', but the model already has one");
    return {};  // the root's pose is then reported lost with the root link
  }
  const std::string name = named_joint ? root.joint_name.str() : std::string("world_joint");
  element(robot_, "link")->SetAttribute("name", "world");
  comment(robot_, "the root's joint to the world, at its initial pose from the file");
  XMLElement* j = element(robot_, "joint");
  j->SetAttribute("name", name.c_str());
  j->SetAttribute("type", root.joint_type == JointType::kFree ? "floating" : "fixed");
  origin(j, root.X_PL);
  element(j, "parent")->SetAttribute("link", "world");
  element(j, "child")->SetAttribute("link", root.name.c_str());
  check_name(name, "joint", source_of(root, LinkSources::kName));
  return name;
}

bool Writer::run() {
  if (!has_derived_data()) return false;
  robot_ = doc_.NewElement("robot");
  doc_.InsertEndChild(robot_);
  check_body_name();
  // The declaration tinyxml2 writes for a document (PushHeader writes a shorter one).
  tinyxml2::XMLDeclaration* declaration = doc_.NewDeclaration();
  declaration->Accept(&printer_);
  doc_.DeleteNode(declaration);
  printer_.OpenElement("robot");
  printer_.PushAttribute("name", model_.name.empty() ? "robot" : model_.name.c_str());
  generated_by(robot_, "body2urdf");
  if (options_.mujoco_compiler) {
    // MuJoCo's URDF reader strips the folders of mesh paths unless told not to; ROS ignores
    // the element.
    element(element(robot_, "mujoco"), "compiler")->SetAttribute("strippath", "false");
  }
  flush();
  materials_at_ = text_.size();
  if (!assess_inertias()) {
    output_.fail();
    return false;
  }

  for (const Link& link : model_.links) link_names_.insert(link.name);
  const std::string world_joint = write_world(model_.root());

  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    const Link& link = model_.links[i];
    check_name(link.name, "link", source_of(link, LinkSources::kName));
    XMLElement* link_el = element(robot_, "link");
    link_el->SetAttribute("name", link.name.c_str());
    if (i == 0 && world_joint.empty()) {
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
  if (!world_joint.empty()) joint_names.insert(world_joint);
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

  // Named materials go first, where every reader finds them before their use. They are known
  // only now: printed apart (at the depth of <robot>'s children) and put in after the header.
  std::string materials_text;
  printer_.redirect(materials_text);
  for (const auto& [name, rgba] : materials_.named()) {
    XMLElement* m = element(robot_, "material");
    m->SetAttribute("name", name.c_str());
    element(m, "color")->SetAttribute("rgba", rgba.c_str());
  }
  flush();
  printer_.redirect(text_);
  printer_.CloseElement();
  text_.insert(materials_at_, materials_text);
  return finish(std::move(text_));
}

}  // namespace bodyfmt::urdf
