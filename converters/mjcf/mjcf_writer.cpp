#include "mjcf_writer.h"

#include "cuboid.h"

#include <bodyfmt/angles.h>
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
#include <bodyfmt/physical.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tinyxml2.h>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>

namespace bodyfmt::mjcf {
namespace {

namespace fs = std::filesystem;
using converters::format_number;
std::string vec3(const Eigen::Vector3d& v) { return converters::format_vector(v); }
using converters::nearly_equal;
using tinyxml2::XMLElement;

constexpr std::string_view kTarget = "MJCF (MuJoCo 2.2.2)";
// MuJoCo's mjMINVAL (include/mujoco/mjtnum.h, double build): the smallest mass and principal
// moment mjCModel accepts for a moving body without a welded descendant that carries mass.
constexpr double kMjMinVal = 1e-15;
// Choreonoid's gravity (the MuJoCo default is 9.81).
constexpr double kGravity = 9.80665;
// MuJoCo 2.2.2 reads MJCF with the system's tinyxml2 9, whose parser stops at 100 nested
// elements: <mujoco>, <worldbody>, the bodies, and a body's own children (measured: 96 nested
// bodies load, 97 do not).
constexpr int kMaxBodyDepth = 96;
// Half thickness given to a box with a zero edge.
constexpr double kFlatBoxHalfThickness = 1e-6;
// Distance between the two connect points that make a hinge extra joint.
constexpr double kHingePointSpacing = 0.1;
// MuJoCo 2.2.2's fixed buffers (<size>): its defaults, the most contacts a collision geom makes
// with a plane (box, cylinder and convex mesh: 4), the rows of a contact in the default
// pyramidal cone with condim 3 (2 (condim - 1)), and the caps. njmax costs memory as njmax²
// (the default nstack, 5 njmax² numbers, and efc_AR) and njmax·nv (efc_J): 4,000 rows are
// about 190 MB resident, and beyond MuJoCo's default the rows are held to 2e6 / nv.
constexpr int kDefaultNconmax = 100;
constexpr int kDefaultNjmax = 500;
constexpr long kPlaneContactsPerGeom = 4;
constexpr long kRowsPerContact = 4;
constexpr long kMaxNconmax = 10000;
constexpr long kMaxNjmax = 4000;
constexpr long kJacobianBudget = 2000000;

std::string quat_text(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;
  return fmt::format("{} {} {} {}", format_number(q.w()), format_number(q.x()), format_number(q.y()),
                     format_number(q.z()));
}

using converters::moments_text;

double radians_to_degrees(double a) { return a * 180.0 / kPi; }

/// MuJoCo allows free joints only on bodies of the world body, so a free non-root link becomes
/// a top-level body at its initial world pose: a 6-DoF joint to the parent and a free body in
/// the world give the same motion, only the coordinates differ.
bool detached(const Link& link) { return link.parent >= 0 && link.joint_type == JointType::kFree; }

/// What is written in <inertial>: the link's mass properties after balancing and the
/// small-mass floor.
struct Inertial {
  double mass = 0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// One geom's placement and shape attributes (type, size, mesh).
struct Piece {
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  std::function<void(XMLElement*)> geometry;
  /// The collision geom when it is not `geometry` at `origin`: a mesh that is exactly a box
  /// collides as a box (cuboid.h).
  std::function<void(XMLElement*)> collision_geometry;
  Eigen::Isometry3d collision_origin = Eigen::Isometry3d::Identity();
  std::optional<Material> material;
  /// A mesh MuJoCo cannot hull: written as a visual geom only, and this reported.
  std::optional<converters::PlannedLoss> collision_dropped;
};

class Writer : converters::XmlWriter {
 public:
  Writer(const Model& model, const Derived& derived, const MjcfOptions& options, converters::OutputSet& output,
         DiagnosticSink& sink)
      : XmlWriter(model, derived, output, kTarget, sink), options_(options) {}

  bool run();

 private:
  /// A value the export changed so that MuJoCo accepts it: a loss of the value as given,
  /// reported now and commented in the link's body when it is written.
  void changed(std::size_t link_index, const SourceLocation& at, const std::string& what) {
    // A warning with the old and new values (the user asked for it with --balance-inertia, or
    // MuJoCo cannot load the body otherwise); --strict refuses it as it does a loss.
    report_rule(sink_, "export-value-changed", at, "MuJoCo cannot accept " + what);
    inertia_notes_[link_index].push_back("export-value-changed: " + what);
  }
  std::string unique(std::set<std::string>& used, std::string name) {
    if (used.count(name)) {
      std::string base = name;
      for (int n = 2; used.count(name); ++n) name = fmt::format("{}_{}", base, n);
    }
    used.insert(name);
    return name;
  }
  void place(XMLElement* e, const Eigen::Affine3d& X) {
    if (!X.translation().isZero(0)) e->SetAttribute("pos", vec3(X.translation()).c_str());
    if (!X.linear().isIdentity(0)) e->SetAttribute("quat", quat_text(X.linear()).c_str());
  }

  bool prepare_inertials();
  void write_inertial(XMLElement* body, std::size_t index);
  void write_joint(XMLElement* body, std::size_t index);
  void write_shapes(XMLElement* body, std::size_t index);
  std::vector<Piece> pieces(XMLElement* body, std::size_t link_index, std::size_t shape_index);
  /// The name of the <mesh> asset of a planned mesh, staged as STL; empty when it cannot be.
  std::string mesh_piece(const converters::PlannedPiece& planned);
  std::string mesh_asset(const std::string& file, const Eigen::Vector3d& scale);
  std::string material_name(const Material& material);
  void write_devices(XMLElement* body, std::size_t index);
  std::string site(XMLElement* body, const Device& device, std::size_t device_index);
  void sensor(const Device& device, const char* kind, const std::string& name, const std::string& site_name,
              const Eigen::Vector3d& max, XMLElement* body);
  void write_self_collision_filter();
  void write_size(XMLElement* after);
  void write_equalities();
  void write_actuators();
  void write_keyframe();

  const MjcfOptions& options_;
  // MuJoCo 2.2.2 writes capsules, refuses zero sizes and collides with convex hulls; its
  // materials have an emission, and it reads meshes from STL files only.
  const converters::ShapeTarget shape_target_{"MuJoCo",
                                              /*capsule=*/true,
                                              kFlatBoxHalfThickness,
                                              /*hull_collision=*/true,
                                              /*emissive_color=*/true,
                                              nullptr};
  XMLElement* mujoco_ = nullptr;
  XMLElement* asset_ = nullptr;
  std::vector<Inertial> inertials_;
  std::vector<std::vector<std::string>> inertia_notes_;  // per link, commented before <inertial>
  converters::MaterialNames<Material> materials_;
  std::map<std::string, std::string> mesh_by_key_;
  std::vector<std::tuple<std::string, std::string, Eigen::Vector3d>> mesh_assets_;  // name, file, scale
  const std::string mesh_folder_ = converters::generated_folder(options_.mesh_folder, "assets", output_, model_.name);
  converters::StagedFiles staged_{output_, mesh_folder_};
  std::set<std::string> site_names_, sensor_names_, camera_names_, light_names_, numeric_names_;
  // Sensors in device-id order: (sort key, element).
  std::vector<std::pair<std::pair<int, std::size_t>, XMLElement*>> sensors_;
  std::size_t current_device_ = 0;
  std::vector<std::pair<std::string, std::string>> track_axes_;  // numeric name, data
  std::map<const XMLElement*, std::size_t> link_of_;             // body element -> link
  XMLElement* world_ = nullptr;
  std::vector<XMLElement*> collision_geoms_;
  std::vector<std::size_t> colliding_links_;  // links with a collision geom, in link order
  long equality_rows_ = 0;                    // constraint rows of the <equality> elements
  long limited_joints_ = 0;
};

bool Writer::prepare_inertials() {
  const std::size_t n = model_.links.size();
  inertials_.resize(n);
  inertia_notes_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const MassProperties& mp = derived_.mass[i];
    Inertial& out = inertials_[i];
    out.mass = mp.mass;
    out.com = mp.center_of_mass;
    out.inertia = symmetrized_inertia(mp.inertia);
  }
  // What is physical, and which moving bodies MuJoCo refuses, is the gate's; a link that is not
  // computable was reported by compute_derived (derived-not-finite).
  PhysicalOptions gate;
  gate.balance_inertia = options_.balance_inertia;
  const PhysicalVerdict verdict = assess_physical(model_, derived_, gate);
  bool writable = true;
  for (const PhysicalFinding& f : verdict.findings) {
    const std::size_t i = static_cast<std::size_t>(f.link);
    const Link& link = model_.links[i];
    if (f.defect == PhysicalDefect::kInertiaAsymmetric) {
      // bodycheck's error, at its place: MJCF holds a symmetric tensor, so only
      // --balance-inertia writes one for it, said (the mean of each pair, as bodysim simulates).
      if (options_.balance_inertia) {
        changed(i, f.at, converters::symmetrised_inertia_text(link, f));
      } else {
        writable = false;
        converters::report_asymmetric_inertia_refused(sink_, link, f, "MuJoCo holds a symmetric tensor");
      }
      continue;
    }
    if (f.defect == PhysicalDefect::kNegativeMass) {
      report_physical(sink_, f,
                      fmt::format("link \"{}\" has mass {} kg; MuJoCo refuses negative masses", link.name,
                                  format_number(derived_.mass[i].mass)));
      continue;
    }
    if (f.defect != PhysicalDefect::kNotPositiveDefinite && f.defect != PhysicalDefect::kTriangle) continue;
    if (verdict.links[i].negative_mass) continue;  // refused for its mass
    const std::string hint = converters::nearest_inertia_hint(f);
    if (!f.balanced_by_policy) {
      report_physical(sink_, f,
                      fmt::format("principal moments {} of link \"{}\" are refused by MuJoCo ({}{}); the model is not "
                                  "written",
                                  moments_text(f.principal.moments), link.name, converters::inertia_defect_text(f),
                                  f.validity.negative_moment ? "" : " < 0"),
                      hint + (hint.empty() ? "" : "; ") + "--balance-inertia writes it");
      continue;
    }
    Inertial& out = inertials_[i];
    const Eigen::Matrix3d before = out.inertia;
    out.inertia = f.balanced_inertia();
    changed(i, f.at, converters::balanced_inertia_text(link, f, before, out.inertia));
  }
  if (!verdict.masses_usable || !writable) return false;

  // A moving body MuJoCo refuses (below mjMINVAL, no welded descendant that carries mass) is
  // written with the documented floor.
  for (const PhysicalFinding& f : verdict.findings) {
    if (f.defect != PhysicalDefect::kMovingMassless && f.defect != PhysicalDefect::kMovingBelowMinimum) continue;
    const std::size_t i = static_cast<std::size_t>(f.link);
    Inertial& in = inertials_[i];
    const PrincipalInertia& p = f.principal;
    const Eigen::Vector3d moments = p.moments.cwiseMax(kMinMovingInertia);
    const double mass = std::max(in.mass, kMinMovingMass);
    const Eigen::Matrix3d inertia = p.axes * moments.asDiagonal() * p.axes.transpose();
    changed(i, f.at,
            fmt::format("the mass {} kg and principal moments {} of moving link \"{}\" (MuJoCo refuses a moving body "
                        "below mjMINVAL = 1e-15 when no fixed child carries mass); written as mass {} kg and "
                        "principal moments {}",
                        format_number(in.mass), moments_text(p.moments), model_.links[i].name, format_number(mass),
                        moments_text(moments)));
    in.mass = mass;
    in.inertia = inertia;
  }
  return true;
}

void Writer::write_inertial(XMLElement* body, std::size_t index) {
  const Inertial& in = inertials_[index];
  for (const std::string& note : inertia_notes_[index]) comment(body, note);
  XMLElement* e = element(body, "inertial");
  e->SetAttribute("pos", vec3(in.com).c_str());
  e->SetAttribute("mass", format_number(in.mass).c_str());
  const PrincipalInertia p = principal_inertia(in.inertia);
  // A diagonal positive definite tensor goes as fullinertia (MuJoCo reads it off exactly).
  // Any other tensor goes in its principal form from our decomposition: MuJoCo 2.2.2's
  // eigen-solver stops early and drops small products of inertia (AizuSpider's R_TRACK loses
  // Ixy = -2.2e-8 of 0.033), and fullinertia refuses a semidefinite tensor (a point mass, a
  // massless frame).
  if (p.exact && p.moments[0] > kMjMinVal) {
    const Eigen::Matrix3d& I = in.inertia;
    e->SetAttribute(
        "fullinertia",
        fmt::format("{} {} {} 0 0 0", format_number(I(0, 0)), format_number(I(1, 1)), format_number(I(2, 2))).c_str());
    return;
  }
  if (p.exact) {
    const Eigen::Matrix3d& I = in.inertia;
    e->SetAttribute("diaginertia", vec3(Eigen::Vector3d(I(0, 0), I(1, 1), I(2, 2)).cwiseMax(0.0)).c_str());
    return;
  }
  Eigen::Matrix3d axes = p.axes;
  if (axes.determinant() < 0) axes.col(2) *= -1;
  if (!axes.isIdentity(0)) e->SetAttribute("quat", quat_text(axes).c_str());
  e->SetAttribute("diaginertia", vec3(p.moments.cwiseMax(0.0)).c_str());
}

void Writer::write_joint(XMLElement* body, std::size_t index) {
  const Link& link = model_.links[index];
  const SourceLocation joint_at = source_of(link, LinkSources::kJointType);
  switch (link.joint_type) {
    case JointType::kFixed: return;
    case JointType::kFree:
      if (detached(link))
        comment(body, fmt::format("a free joint relative to '{}' in the model: a top-level body in MuJoCo",
                                  model_.links[static_cast<std::size_t>(link.parent)].name));
      element(body, "freejoint")->SetAttribute("name", link.name.c_str());
      return;
    case JointType::kPseudoContinuousTrack: {
      // MuJoCo 2.2.2 has no surface velocity: the track stays a welded body with its geoms and
      // its axis is kept for a controller (dynamics-checker.md §3.2).
      const Eigen::Vector3d axis = written_axis(body, index);
      const std::string name = unique(numeric_names_, "track_axis:" + link.name);
      track_axes_.emplace_back(name, vec3(axis));
      loss(converters::LossKind::kTracks, body, joint_at,
           fmt::format("the pseudo_continuous_track of '{}': MuJoCo 2.2.2 has no surface velocity (the body is "
                       "welded; its axis {} is kept as <custom><numeric name=\"{}\">)",
                       link.name, vec3(axis), name),
           "drive it from mjcb_control as in dynamics-checker.md §3.2");
      return;
    }
    case JointType::kRevolute:
    case JointType::kPrismatic: break;
  }
  const Eigen::Vector3d axis = written_axis(body, index);  // its report comes before the joint
  XMLElement* j = element(body, "joint");
  j->SetAttribute("name", link.name.c_str());
  j->SetAttribute("type", link.joint_type == JointType::kRevolute ? "hinge" : "slide");
  j->SetAttribute("pos", "0 0 0");
  j->SetAttribute("axis", vec3(axis).c_str());
  const double lo = link.joint_range_lower, hi = link.joint_range_upper;
  const bool lo_finite = lo > -kUnlimited, hi_finite = hi < kUnlimited;
  if (lo_finite && hi_finite) {
    j->SetAttribute("limited", "true");
    ++limited_joints_;
    // MuJoCo wants lower < upper; a joint that cannot move keeps its degree of freedom (joint
    // ids and qpos stay as in the model) in the narrowest range MuJoCo accepts.
    const double upper = lo < hi ? hi : std::nextafter(lo, kUnlimited);
    if (upper != hi)
      changed(index, source_of(link, LinkSources::kJointRange),
              fmt::format("the zero-width range [{0}, {0}] of '{1}' (written [{0}, {2}])", format_number(lo), link.name,
                          format_number(upper)));
    j->SetAttribute("range", fmt::format("{} {}", format_number(lo), format_number(upper)).c_str());
  } else {
    j->SetAttribute("limited", "false");
    if (lo_finite || hi_finite) {
      loss(converters::LossKind::kJoints, body, source_of(link, LinkSources::kJointRange),
           fmt::format("the one-sided range [{}, {}] of '{}' (MuJoCo limits need both bounds; written unlimited)",
                       lo_finite ? format_number(lo) : "-inf", hi_finite ? format_number(hi) : "inf", link.name));
    }
  }
  if (link.joint_axis_inertia != 0) j->SetAttribute("armature", format_number(link.joint_axis_inertia).c_str());
  const bool velocity_limited = link.velocity_lower > -kUnlimited || link.velocity_upper < kUnlimited;
  const bool effort_limited = link.effort_lower > -kUnlimited || link.effort_upper < kUnlimited;
  std::vector<std::string> lost;
  if (velocity_limited && options_.actuators != Actuators::kVelocity) lost.push_back("velocity");
  if (effort_limited && options_.actuators == Actuators::kNone) lost.push_back("effort");
  if (!lost.empty()) {
    loss(converters::LossKind::kJoints, body, source_of(link, LinkSources::kJointVelocity),
         fmt::format("the {} limits of '{}' (MuJoCo joints have none)", fmt::join(lost, " and "), link.name),
         lost.size() == 2 || lost[0] == "velocity" ? "--actuators velocity writes them as control and force ranges"
                                                   : "--actuators writes it as a force range");
  }
}

std::string Writer::material_name(const Material& m) {
  const std::string key = fmt::format("{}|{}|{}|{}|{}|{}", vec3(m.diffuse_color), vec3(m.specular_color),
                                      vec3(m.emissive_color), format_number(m.specular_exponent),
                                      format_number(m.transparency), format_number(m.ambient_intensity));
  return materials_.name(key, m);
}

std::string Writer::mesh_asset(const std::string& file, const Eigen::Vector3d& scale) {
  const std::string key = file + "|" + vec3(scale);
  auto it = mesh_by_key_.find(key);
  if (it != mesh_by_key_.end()) return it->second;
  std::string name = fs::path(file).stem().string();
  std::set<std::string> used;
  for (const auto& a : mesh_assets_) used.insert(std::get<0>(a));
  name = unique(used, name);
  mesh_assets_.emplace_back(name, file, scale);
  mesh_by_key_.emplace(key, name);
  return name;
}

std::string Writer::mesh_piece(const converters::PlannedPiece& planned) {
  std::string error;
  const std::optional<std::string> relative =
      staged_.mesh(planned.key, planned.stem, *planned.mesh, std::nullopt, converters::MeshFormat::kStl, error);
  if (!relative) {
    fatal("export-write", model_.source, error);
    return {};
  }
  // <mesh file> is relative to the compiler's meshdir (the staging folder).
  const std::string prefix = mesh_folder_ + "/";
  const std::string file = relative->rfind(prefix, 0) == 0 ? relative->substr(prefix.size()) : *relative;
  return mesh_asset(file, planned.scale);
}

std::vector<Piece> Writer::pieces(XMLElement* body, std::size_t link_index, std::size_t shape_index) {
  const Shape& shape = model_.links[link_index].shapes[shape_index];
  converters::ShapePlan plan = converters::plan_shape(model_, link_index, shape_index, shape_target_, sink_);
  for (const converters::PlannedLoss& planned : plan.losses) loss(body, planned);
  std::vector<Piece> out;
  for (converters::PlannedPiece& planned : plan.pieces) {
    Piece piece;
    piece.origin = planned.origin;
    piece.material = planned.material;
    piece.collision_dropped = std::move(planned.collision_dropped);
    auto typed = [](const char* type, std::string size) {
      return [type, size = std::move(size)](XMLElement* g) {
        g->SetAttribute("type", type);
        g->SetAttribute("size", size.c_str());
      };
    };
    // MuJoCo sizes are half edges and half lengths.
    auto round = [&planned] { return format_number(planned.radius) + " " + format_number(planned.length / 2); };
    using Kind = converters::PlannedPiece::Kind;
    switch (planned.kind) {
      case Kind::kBox: piece.geometry = typed("box", vec3(planned.size / 2)); break;
      case Kind::kSphere: piece.geometry = typed("sphere", format_number(planned.radius)); break;
      case Kind::kCylinder: piece.geometry = typed("cylinder", round()); break;
      case Kind::kCapsule: piece.geometry = typed("capsule", round()); break;
      case Kind::kMesh:
      case Kind::kMeshFile: {  // no file is referenced as it is (shape_target_)
        // MuJoCo 2.2.2 collides a mesh with a plane at its deepest vertex and at most two hull
        // neighbours, a box at its corners: a mesh that is exactly a box collides as one.
        std::optional<Cuboid> box;
        if (shape.collision && !piece.collision_dropped && planned.mesh)
          box = exact_cuboid(*planned.mesh, planned.scale);
        if (box) {
          piece.collision_geometry = typed("box", vec3(box->half_edges));
          piece.collision_origin = piece.origin * box->pose;
          if (!shape.visual) break;  // no mesh file for a collision-only box
        }
        const std::string name = mesh_piece(planned);
        if (name.empty()) continue;
        piece.geometry = [name](XMLElement* g) {
          g->SetAttribute("type", "mesh");
          g->SetAttribute("mesh", name.c_str());
        };
        break;
      }
    }
    out.push_back(std::move(piece));
  }
  return out;
}

void Writer::write_shapes(XMLElement* body, std::size_t index) {
  const Link& link = model_.links[index];
  for (std::size_t s = 0; s < link.shapes.size(); ++s) {
    const Shape& shape = link.shapes[s];
    for (Piece& piece : pieces(body, index, s)) {
      // body-format-spec §7.3: under Visual visual only, under Collision collision only, under
      // neither both. Visual geoms: group 2, no contact, no mass; collision geoms: group 3.
      if (piece.collision_dropped) loss(body, *piece.collision_dropped);
      for (bool visual : {true, false}) {
        if (visual ? !shape.visual : !shape.collision || piece.collision_dropped) continue;
        const bool as_box = !visual && piece.collision_geometry;
        if (as_box)
          comment(body,
                  "a collision mesh that is exactly a box, written as a box: the same geometry, and MuJoCo "
                  "collides a box with a plane at its corners, a mesh at up to 3 vertices");
        XMLElement* g = element(body, "geom");
        place(g, as_box ? piece.collision_origin : piece.origin);
        (as_box ? piece.collision_geometry : piece.geometry)(g);
        if (visual) {
          g->SetAttribute("group", 2);
          g->SetAttribute("contype", 0);
          g->SetAttribute("conaffinity", 0);
          g->SetAttribute("mass", 0);
          if (piece.material) g->SetAttribute("material", material_name(*piece.material).c_str());
        } else {
          g->SetAttribute("group", 3);
          collision_geoms_.push_back(g);
          if (colliding_links_.empty() || colliding_links_.back() != index) colliding_links_.push_back(index);
        }
      }
    }
  }
}

std::string Writer::site(XMLElement* body, const Device& device, std::size_t device_index) {
  const Link& link = model_.links[static_cast<std::size_t>(device.link)];
  const std::string name = unique(
      site_names_, device.name.empty() ? fmt::format("{}_{}_{}", link.name, device.type, device_index) : device.name);
  check_xml_name(name, "device", device.source);
  XMLElement* s = element(body, "site");
  s->SetAttribute("name", name.c_str());
  place(s, device.X_LD);
  return name;
}

void Writer::sensor(const Device& device, const char* kind, const std::string& name, const std::string& site_name,
                    const Eigen::Vector3d& max, XMLElement* body) {
  XMLElement* e = doc_.NewElement(kind);
  e->SetAttribute("name", unique(sensor_names_, name).c_str());
  e->SetAttribute("site", site_name.c_str());
  // MuJoCo's cutoff clips every axis to one bound.
  if ((max.array() < kUnlimited).any()) {
    if (nearly_equal(max.x(), max.y()) && nearly_equal(max.x(), max.z())) {
      e->SetAttribute("cutoff", format_number(max.x()).c_str());
    } else {
      const Eigen::Vector3d shown = max.unaryExpr([](double v) { return converters::finite_or_stand_in(v); });
      loss(converters::LossKind::kDevices, body, device.source,
           fmt::format("the per-axis limits {} of {} sensor '{}' (MuJoCo's cutoff is one bound; not written)",
                       vec3(shown), kind, name));
    }
  }
  sensors_.push_back({{device.id >= 0 ? device.id : INT32_MAX, current_device_}, e});
}

void Writer::write_devices(XMLElement* body, std::size_t index) {
  for (std::size_t d = 0; d < model_.devices.size(); ++d) {
    const Device& device = model_.devices[d];
    if (device.link != static_cast<LinkIndex>(index)) continue;
    current_device_ = d;
    const std::string label = device.name.empty() ? device.type : device.name;
    if (const auto* camera = std::get_if<CameraParams>(&device.params)) {
      // MuJoCo cameras look along -Z with +Y up, as Choreonoid's default "gl" optical frame
      // (body-format-spec §10.3); the other frames are rotated onto it, and
      // optical_frame_rotation is post-multiplied.
      Eigen::Matrix3d R_optical = Eigen::Matrix3d::Identity();
      if (camera->optical_frame == "cv") R_optical = Eigen::Vector3d(1, -1, -1).asDiagonal();
      if (camera->optical_frame == "robotics") R_optical << 0, 0, -1, -1, 0, 0, 0, 1, 0;
      Eigen::Isometry3d X = device.X_LD;
      X.linear() = device.X_LD.linear() * R_optical * camera->optical_frame_rotation;
      XMLElement* c = element(body, "camera");
      const std::string name = unique(
          camera_names_, device.name.empty() ? fmt::format("{}_camera_{}", model_.links[index].name, d) : device.name);
      check_xml_name(name, "device", device.source);
      c->SetAttribute("name", name.c_str());
      c->SetAttribute("mode", "fixed");
      place(c, X);
      // Choreonoid's field of view spans the shorter image side; MuJoCo's fovy is vertical and
      // always in degrees.
      double fovy = camera->field_of_view;
      if (camera->width < camera->height && camera->height > 0)
        fovy = 2 * std::atan(std::tan(camera->field_of_view / 2) * camera->height / camera->width);
      c->SetAttribute("fovy", format_number(radians_to_degrees(fovy)).c_str());
      loss(converters::LossKind::kDevices, body, device.source,
           fmt::format("the resolution {}x{}, frame rate, clip distances{} of camera '{}' (MuJoCo 2.2.2 cameras have "
                       "none)",
                       camera->width, camera->height,
                       camera->lens_type != "NORMAL" ? fmt::format(" and {} lens", camera->lens_type) : "", label));
    } else if (const auto* light = std::get_if<LightParams>(&device.params)) {
      if (device.type == "SpotLight" && light->direction.norm() < 1e-9) {
        // MuJoCo refuses a light without a direction ("zero direction in light").
        loss(converters::LossKind::kDevices, body, device.source,
             fmt::format("spot light '{}' with the zero direction [0, 0, 0] (not written)", label),
             "give the light a direction, e.g. direction: [0, 0, -1]");
        continue;
      }
      XMLElement* l = element(body, "light");
      const std::string name = unique(
          light_names_, device.name.empty() ? fmt::format("{}_light_{}", model_.links[index].name, d) : device.name);
      check_xml_name(name, "device", device.source);
      l->SetAttribute("name", name.c_str());
      l->SetAttribute("mode", "fixed");
      l->SetAttribute("pos", vec3(device.X_LD.translation()).c_str());
      const bool spot = device.type == "SpotLight";
      const Eigen::Vector3d dir = device.X_LD.linear() * (spot ? light->direction : Eigen::Vector3d(0, 0, -1));
      l->SetAttribute("dir", vec3(dir.normalized()).c_str());
      l->SetAttribute("diffuse", vec3(Eigen::Vector3d(light->color * light->intensity)).c_str());
      l->SetAttribute("attenuation", vec3(light->attenuation).c_str());
      // A point light is an OpenGL spot with a 180° cutoff; MuJoCo's cutoff is in degrees.
      l->SetAttribute("cutoff", format_number(spot ? radians_to_degrees(light->cut_off_angle) : 180.0).c_str());
      if (spot) l->SetAttribute("exponent", format_number(light->cut_off_exponent).c_str());
      if (!device.on) l->SetAttribute("active", "false");
      if (spot)
        loss(converters::LossKind::kDevices, body, device.source,
             fmt::format("the beam width of spot light '{}'", label));
    } else if (const auto* force = std::get_if<ForceSensorParams>(&device.params)) {
      const std::string s = site(body, device, d);
      sensor(device, "force", s + "_force", s, force->max_force, body);
      sensor(device, "torque", s + "_torque", s, force->max_torque, body);
    } else if (const auto* inertial = std::get_if<InertialSensorParams>(&device.params)) {
      const std::string s = site(body, device, d);
      const bool imu = device.type == "Imu";
      if (imu || device.type == "RateGyroSensor")
        sensor(device, "gyro", imu ? s + "_gyro" : s, s, inertial->max_angular_velocity, body);
      if (imu || device.type == "AccelerationSensor")
        sensor(device, "accelerometer", imu ? s + "_accelerometer" : s, s, inertial->max_acceleration, body);
    } else {
      loss(converters::LossKind::kDevices, body, device.source, fmt::format("device '{}' ({})", label, device.type));
    }
  }
}

void Writer::write_self_collision_filter() {
  if (options_.self_collision || colliding_links_.size() < 2) return;
  if (options_.collision_group == 0 && colliding_links_.size() <= kMaxExcludeBodies) {
    // Every pair, parent and child included: MuJoCo's own parent filter skips a parent welded
    // to the world (a fixed root and its first links would touch).
    XMLElement* contact = element(mujoco_, "contact");
    comment(contact,
            "self-collision off, as Choreonoid simulates a body by default: every pair of this model's bodies "
            "is excluded (--self-collision keeps MuJoCo's rule)");
    for (std::size_t a = 0; a < colliding_links_.size(); ++a) {
      for (std::size_t b = a + 1; b < colliding_links_.size(); ++b) {
        XMLElement* e = element(contact, "exclude");
        e->SetAttribute("body1", model_.links[colliding_links_[a]].name.c_str());
        e->SetAttribute("body2", model_.links[colliding_links_[b]].name.c_str());
      }
    }
    return;
  }
  // Pairwise excludes grow with the square of the bodies (5e9 for a 100,000-link star): the
  // contact bits of one group keep the model's geoms apart instead.
  const int group = options_.collision_group > 0 ? options_.collision_group : collision_group_of(model_.name);
  const unsigned bit = 1u << group;
  const std::string contype = std::to_string(bit);
  const std::string conaffinity = std::to_string(0x7fffffffu & ~bit);
  comment(world_, fmt::format("self-collision off, as Choreonoid simulates a body by default: collision geoms are in "
                              "contact group {} (contype {}, conaffinity {}); they touch default geoms and other "
                              "groups, not each other (--collision-group, --self-collision)",
                              group, contype, conaffinity));
  for (XMLElement* g : collision_geoms_) {
    g->SetAttribute("contype", contype.c_str());
    g->SetAttribute("conaffinity", conaffinity.c_str());
  }
}

void Writer::write_size(XMLElement* after) {
  // Room for every collision geom on a floor at once (a fixed root at the origin of a floor
  // plane, as Robotiq's 2F-85 has, makes 288 contacts from 87 boxes), each contact's rows, a
  // row per joint limit and the equality rows.
  long nv = 0;
  for (const Link& link : model_.links) {
    if (link.joint_type == JointType::kFree) nv += 6;
    if (link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic) nv += 1;
  }
  const long contacts = kPlaneContactsPerGeom * static_cast<long>(collision_geoms_.size());
  const long rows = kRowsPerContact * contacts + limited_joints_ + equality_rows_;
  const long row_cap = std::max<long>(kDefaultNjmax, std::min(kMaxNjmax, kJacobianBudget / std::max(nv, 1L)));
  const long nconmax = std::clamp<long>(contacts, kDefaultNconmax, kMaxNconmax);
  const long njmax = std::clamp<long>(rows, kDefaultNjmax, row_cap);
  XMLElement* size = doc_.NewElement("size");
  mujoco_->InsertAfterChild(after, size);
  size->SetAttribute("nconmax", static_cast<int64_t>(nconmax));
  size->SetAttribute("njmax", static_cast<int64_t>(njmax));
  if (nconmax < contacts || njmax < rows)
    mujoco_->InsertAfterChild(
        after, doc_.NewComment(fmt::format(" buffers capped: {} contacts and {} constraint rows would hold every "
                                           "collision geom on a floor ",
                                           contacts, rows)
                                   .c_str()));
}

void Writer::write_equalities() {
  XMLElement* equality = nullptr;
  auto eq = [&](const char* kind) {
    if (!equality) equality = element(mujoco_, "equality");
    return element(equality, kind);
  };
  for (const ExtraJoint& ej : model_.extra_joints) {
    if (ej.link1 < 0 || ej.link2 < 0) continue;
    const std::size_t i1 = static_cast<std::size_t>(ej.link1), i2 = static_cast<std::size_t>(ej.link2);
    const std::string& l1 = model_.links[i1].name;
    const std::string& l2 = model_.links[i2].name;
    const std::string what = fmt::format("the {} extra joint between '{}' and '{}'", ej.type, l1, l2);
    if (ej.type == "piston") {
      loss(converters::LossKind::kExtraJoints, mujoco_, ej.source,
           what + " (MuJoCo has no equality constraint for it)");
      continue;
    }
    // MuJoCo 2.2.2 takes body2's side of a connect from the initial configuration (qpos0), so
    // the loop must be closed there.
    const Eigen::Affine3d W1 = derived_.X_WL[i1] * ej.X_1J, W2 = derived_.X_WL[i2] * ej.X_2J;
    const double gap = (W1.translation() - W2.translation()).norm();
    if (ej.type == "fixed") {
      XMLElement* w = eq("weld");
      equality_rows_ += 6;
      w->SetAttribute("body1", l1.c_str());
      w->SetAttribute("body2", l2.c_str());
      const Eigen::Isometry3d X_12 = ej.X_1J * ej.X_2J.inverse();  // body2 in body1
      w->SetAttribute("relpose", (vec3(X_12.translation()) + " " + quat_text(X_12.linear())).c_str());
      continue;
    }
    std::vector<Eigen::Vector3d> anchors = {ej.X_1J.translation()};
    if (ej.type == "hinge") {
      // A hinge is two connects on its axis.
      const Eigen::Vector3d axis = (ej.X_1J.linear() * ej.axis).normalized();
      anchors.push_back(ej.X_1J.translation() + kHingePointSpacing * axis);
    } else if (ej.type != "ball") {
      loss(converters::LossKind::kExtraJoints, mujoco_, ej.source, what);
      continue;
    }
    for (const Eigen::Vector3d& a : anchors) {
      XMLElement* c = eq("connect");
      equality_rows_ += 3;
      c->SetAttribute("body1", l1.c_str());
      c->SetAttribute("body2", l2.c_str());
      c->SetAttribute("anchor", vec3(a).c_str());
    }
    if (gap > 1e-9) {
      loss(converters::LossKind::kExtraJoints, mujoco_, ej.source,
           fmt::format("{} as given: its two points are {} m apart at the initial pose, and MuJoCo 2.2.2 takes the "
                       "point on '{}' from there",
                       what, format_number(gap), l2));
    }
  }
}

void Writer::write_actuators() {
  if (options_.actuators == Actuators::kNone) return;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    const JointType t = model_.links[i].joint_type;
    if (t == JointType::kRevolute || t == JointType::kPrismatic) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const int ia = model_.links[a].joint_id, ib = model_.links[b].joint_id;
    return (ia >= 0 ? ia : INT32_MAX) < (ib >= 0 ? ib : INT32_MAX);
  });
  if (order.empty()) return;
  XMLElement* actuator = element(mujoco_, "actuator");
  const bool position = options_.actuators == Actuators::kPosition;
  for (std::size_t i : order) {
    const Link& link = model_.links[i];
    // MuJoCo wants lower < upper here too: an empty range is written as the narrowest one it
    // accepts (as the joint's own range is, which write_joint reports), a reversed one as no
    // limit; both reported.
    auto range = [&](XMLElement* e, const char* limited, const char* range, double lo, double hi,
                     const SourceLocation& at, bool joint_range) {
      const bool finite = lo > -kUnlimited && hi < kUnlimited;
      if (finite && lo > hi)
        loss(converters::LossKind::kJoints, e, first_known({at, link.source}),
             fmt::format("the reversed {} [{}, {}] of actuator '{}' (written unlimited)", range, format_number(lo),
                         format_number(hi), link.name));
      if (finite && lo <= hi) {
        const double upper = lo < hi ? hi : std::nextafter(lo, kUnlimited);
        if (upper != hi && !joint_range)
          value_changed(e, first_known({at, link.source}),
                        fmt::format("MuJoCo cannot accept the zero-width {0} [{1}, {1}] of actuator '{2}' (written "
                                    "[{1}, {3}])",
                                    range, format_number(lo), link.name, format_number(upper)));
        e->SetAttribute(limited, "true");
        e->SetAttribute(range, fmt::format("{} {}", format_number(lo), format_number(upper)).c_str());
      } else {
        e->SetAttribute(limited, "false");
      }
    };
    XMLElement* a = element(actuator, position ? "position" : "velocity");
    a->SetAttribute("name", link.name.c_str());
    a->SetAttribute("joint", link.name.c_str());
    if (position)
      range(a, "ctrllimited", "ctrlrange", link.joint_range_lower, link.joint_range_upper, link.sources.joint_range(),
            true);
    else
      range(a, "ctrllimited", "ctrlrange", link.velocity_lower, link.velocity_upper, link.sources.joint_velocity(),
            false);
    range(a, "forcelimited", "forcerange", link.effort_lower, link.effort_upper, link.source, false);
  }
}

void Writer::write_keyframe() {
  bool displaced = false;
  for (const Link& link : model_.links) displaced = displaced || link.initial_displacement != 0;
  if (!displaced) return;
  // qpos follows MuJoCo's body order: the document's depth-first order of <body> elements.
  std::vector<std::string> qpos;
  std::vector<const XMLElement*> stack;
  for (const XMLElement* b = world_->LastChildElement("body"); b; b = b->PreviousSiblingElement("body"))
    stack.push_back(b);
  while (!stack.empty()) {
    const XMLElement* b = stack.back();
    stack.pop_back();
    for (const XMLElement* c = b->LastChildElement("body"); c; c = c->PreviousSiblingElement("body"))
      stack.push_back(c);
    const std::size_t i = link_of_.at(b);
    const Link& link = model_.links[i];
    if (link.joint_type == JointType::kFree) {
      qpos.push_back(vec3(derived_.X_WL[i].translation()));
      qpos.push_back(quat_text(derived_.X_WL[i].linear()));
    } else if (link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic) {
      qpos.push_back(format_number(link.initial_displacement));
    }
  }
  XMLElement* key = element(element(mujoco_, "keyframe"), "key");
  key->SetAttribute("name", "initial");
  key->SetAttribute("qpos", fmt::format("{}", fmt::join(qpos, " ")).c_str());
}

bool Writer::run() {
  if (!has_derived_data()) return false;
  if (!prepare_inertials()) {
    output_.fail();
    return false;
  }
  // Checked before any element exists: tinyxml2 also builds, prints and frees documents
  // recursively, so a 100,000-link chain must never become one.
  std::vector<int> depth(model_.links.size(), 1);
  for (std::size_t i = 1; i < model_.links.size(); ++i) {
    const Link& link = model_.links[i];
    if (link.parent >= 0 && !detached(link)) depth[i] = depth[static_cast<std::size_t>(link.parent)] + 1;
    if (depth[i] > kMaxBodyDepth) {
      fatal("export-write", source_of(link, LinkSources::kName),
            fmt::format("link \"{}\" is {} bodies deep; MuJoCo 2.2.2 reads MJCF with tinyxml2, which stops at 100 "
                        "nested elements ({} nested bodies), so nothing is written",
                        link.name, depth[i], kMaxBodyDepth));
      output_.fail();
      return false;
    }
  }
  doc_.InsertEndChild(doc_.NewDeclaration());
  mujoco_ = doc_.NewElement("mujoco");
  doc_.InsertEndChild(mujoco_);
  check_body_name();
  mujoco_->SetAttribute("model", model_.name.empty() ? "body" : model_.name.c_str());
  generated_by(mujoco_, "body2mjcf");
  // Every unit and default that matters is written: radians, limits only where stated, the
  // inertials as given (no mass from geoms, no bounds, no balancing by MuJoCo).
  XMLElement* compiler = element(mujoco_, "compiler");
  compiler->SetAttribute("angle", "radian");
  compiler->SetAttribute("autolimits", "false");
  compiler->SetAttribute("meshdir", mesh_folder_.c_str());
  compiler->SetAttribute("inertiafromgeom", "false");
  compiler->SetAttribute("boundmass", 0);
  compiler->SetAttribute("boundinertia", 0);
  compiler->SetAttribute("balanceinertia", "false");
  XMLElement* option = element(mujoco_, "option");
  option->SetAttribute("timestep", "0.001");
  option->SetAttribute("gravity", vec3(Eigen::Vector3d(0, 0, -kGravity)).c_str());
  asset_ = element(mujoco_, "asset");
  XMLElement* world = element(mujoco_, "worldbody");
  world_ = world;

  std::vector<XMLElement*> bodies(model_.links.size(), nullptr);
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    const Link& link = model_.links[i];
    const SourceLocation name_at = source_of(link, LinkSources::kName);
    check_xml_name(link.name, "link", name_at);
    if (link.name == "world")
      fatal("export-name-conflict", name_at, "a link named 'world' clashes with MuJoCo's world body");
    // Links are in depth-first pre-order, so a parent's element exists before its children.
    XMLElement* parent = link.parent < 0 || detached(link) ? world : bodies[static_cast<std::size_t>(link.parent)];
    XMLElement* body = element(parent, "body");
    bodies[i] = body;
    link_of_.emplace(body, i);
    body->SetAttribute("name", link.name.c_str());
    place(body, detached(link) ? derived_.X_WL[i] : link.X_PL);
    if (link.joint_id >= 0) comment(body, fmt::format("joint_id {}", link.joint_id));
    write_joint(body, i);
    write_inertial(body, i);
    write_shapes(body, i);
    if (!link.contact_material.empty() && link.contact_material != "default")
      loss(converters::LossKind::kDynamics, body, link.source,
           fmt::format("the contact material '{}'", link.contact_material.str()));
    if (!link.actuation_mode.empty() && link.joint_type != JointType::kPseudoContinuousTrack)
      loss(converters::LossKind::kDynamics, body, link.source,
           fmt::format("the actuation mode '{}'", link.actuation_mode.str()),
           "--actuators adds position or velocity actuators");
    write_devices(body, i);
  }
  write_self_collision_filter();
  write_equalities();
  write_size(option);
  write_actuators();
  if (!sensors_.empty()) {
    std::stable_sort(sensors_.begin(), sensors_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    XMLElement* sensor = element(mujoco_, "sensor");
    for (auto& s : sensors_) sensor->InsertEndChild(s.second);
  }
  if (!track_axes_.empty()) {
    XMLElement* custom = element(mujoco_, "custom");
    for (const auto& [name, data] : track_axes_) {
      XMLElement* n = element(custom, "numeric");
      n->SetAttribute("name", name.c_str());
      n->SetAttribute("size", 3);
      n->SetAttribute("data", data.c_str());
    }
  }
  write_keyframe();

  for (const auto& [name, m] : materials_.named()) {
    XMLElement* e = element(asset_, "material");
    e->SetAttribute("name", name.c_str());
    // Clamped: MuJoCo refuses a float overflow.
    e->SetAttribute("rgba", converters::format_vector(converters::clamped_rgba(m)).c_str());
    // MuJoCo has scalar specular, shininess and emission (emission scales rgba): the colours'
    // means, and the exponent back on VRML's 0..1 shininess (exponent = 127 shininess + 1).
    e->SetAttribute("specular", format_number(std::clamp(m.specular_color.mean(), 0.0, 1.0)).c_str());
    e->SetAttribute("shininess", format_number(std::clamp((m.specular_exponent - 1.0) / 127.0, 0.0, 1.0)).c_str());
    const double diffuse = m.diffuse_color.mean();
    e->SetAttribute("emission",
                    format_number(diffuse > 0 ? std::clamp(m.emissive_color.mean() / diffuse, 0.0, 1.0) : 0.0).c_str());
  }
  for (const auto& [name, file, scale] : mesh_assets_) {
    XMLElement* e = element(asset_, "mesh");
    e->SetAttribute("name", name.c_str());
    e->SetAttribute("file", file.c_str());
    if (!(scale.array() == 1.0).all()) e->SetAttribute("scale", vec3(scale).c_str());
  }
  if (asset_->NoChildren()) mujoco_->DeleteChild(asset_);

  tinyxml2::XMLPrinter printer;
  if (!failed_) doc_.Print(&printer);
  return finish(std::string(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1)));
}

}  // namespace

int collision_group_of(const std::string& model_name) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : model_name) h = (h ^ c) * 16777619u;
  return 1 + static_cast<int>(h % kMaxCollisionGroup);
}

bool write_mjcf(const Model& model, const Derived& derived, const MjcfOptions& options, converters::OutputSet& output,
                DiagnosticSink& sink) {
  return converters::write_xml<Writer>(model, derived, options, output, sink, "MJCF");
}

}  // namespace bodyfmt::mjcf
