#include "bodyinfo_report.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/text.h>

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <ostream>
#include <utility>

#include <cmath>

namespace bodyfmt::tools {
namespace {

void append_number(std::string& out, double v) {
  if (std::isinf(v) || std::abs(v) >= kUnlimited) {
    out += v > 0 ? ".inf" : "-.inf";
  } else if (std::isnan(v)) {
    out += ".nan";
  } else if (v == 0) {
    out += '0';  // no "-0"
  } else {
    fmt::format_to(std::back_inserter(out), FMT_COMPILE("{}"), v);
  }
}

std::string number(double v) {
  std::string out;
  append_number(out, v);
  return out;
}

template <typename Vector>
std::string list(const Vector& v) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + number(v[i]);
  return out + "]";
}

std::string matrix(const Eigen::Matrix3d& m) {
  std::string out = "[";
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out += (r || c ? ", " : "") + number(m(r, c));
  return out + "]";
}

std::string quoted(const std::string& s) { return text::yaml_quote(s); }

std::string bbox(const BoundingBox& b) {
  return "[" + number(b.min.x()) + ", " + number(b.min.y()) + ", " + number(b.min.z()) + ", " + number(b.max.x()) +
         ", " + number(b.max.y()) + ", " + number(b.max.z()) + "]";
}

std::string pair(double lo, double hi) { return "[" + number(lo) + ", " + number(hi) + "]"; }

double degrees(double radians) { return radians * 180.0 / kPi; }

// " range ..." of a revolute or prismatic joint.
void append_range(std::string& out, const Link& link) {
  if (link.joint_type != JointType::kRevolute && link.joint_type != JointType::kPrismatic) return;
  if (link.joint_range_lower <= -kUnlimited && link.joint_range_upper >= kUnlimited) {
    out += " range unlimited";
    return;
  }
  auto end = [&](double v) {
    if (std::abs(v) >= kUnlimited) {
      out += v > 0 ? "+inf" : "-inf";
    } else if (link.joint_type == JointType::kRevolute) {
      fmt::format_to(std::back_inserter(out), FMT_COMPILE("{:.4g} deg"), degrees(v));
    } else {
      fmt::format_to(std::back_inserter(out), FMT_COMPILE("{:.4g} m"), v);
    }
  };
  out += " range [";
  end(link.joint_range_lower);
  out += ", ";
  end(link.joint_range_upper);
  out += ']';
}

// Links are stored in depth-first pre-order (model.h), so one pass in order prints the tree;
// nothing recurses per level, and a deep chain (a cable, a snake robot) indents at most
// kMaxIndent levels and shows its depth instead of growing the output quadratically.
constexpr int kMaxIndent = 32;

void summary_link(std::string& out, const Model& model, const Derived& derived, LinkIndex i, int depth) {
  // Appended in place, without temporary strings, through format strings parsed at compile
  // time (parsing them at run time was 2 % of bodyinfo on a 100,000-link chain).
  const Link& link = model.links[static_cast<std::size_t>(i)];
  const MassProperties& m = derived.mass[static_cast<std::size_t>(i)];
  auto to = std::back_inserter(out);
  out.append(static_cast<std::size_t>(std::min(depth, kMaxIndent) * 2), ' ');
  if (depth > kMaxIndent) fmt::format_to(to, FMT_COMPILE("[depth {}] "), depth);
  out += link.name;
  out += "  (";
  out += joint_type_name(link.joint_type);
  if (link.joint_id >= 0) fmt::format_to(to, FMT_COMPILE(" #{}"), link.joint_id);
  if (link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic ||
      link.joint_type == JointType::kPseudoContinuousTrack) {
    out += " axis [";
    for (Eigen::Index k = 0; k < link.joint_axis.size(); ++k) {
      if (k > 0) out += ", ";
      append_number(out, link.joint_axis[k]);
    }
    out += ']';
  }
  append_range(out, link);
  fmt::format_to(to, FMT_COMPILE(")  {:.6g} kg\n"), m.mass);
}

}  // namespace

void write_summary(std::ostream& os, const Model& model, const Derived& derived) {
  // Written in blocks: the text of a 100,000-link chain is 14 MB, which need not be held whole.
  constexpr std::size_t kBlock = 64 * 1024;
  std::string out;
  out.reserve(kBlock + 1024);
  out += fmt::format("{}: {} links, {} joints, {} devices, {:.6g} kg, format {} ({})\n", model.name, model.links.size(),
                     model.num_joints(), model.devices.size(), derived.total_mass, model.format_version,
                     model.angles_in_degrees ? "degrees" : "radians");
  out += "links:\n";
  // Links are in depth-first pre-order, so a parent's depth is known before its children's.
  std::vector<int> depth(model.links.size(), 1);
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(model.links.size()); ++i) {
    const LinkIndex parent = model.links[static_cast<std::size_t>(i)].parent;
    if (parent >= 0) depth[static_cast<std::size_t>(i)] = depth[static_cast<std::size_t>(parent)] + 1;
    summary_link(out, model, derived, i, depth[static_cast<std::size_t>(i)]);
    if (out.size() >= kBlock) {
      os.write(out.data(), static_cast<std::streamsize>(out.size()));
      out.clear();
    }
  }
  if (!model.devices.empty()) {
    out += "devices:\n";
    for (const Device& d : model.devices)
      out += fmt::format("  {} {}{} on {}{}\n", d.type, d.name.empty() ? "(unnamed)" : d.name,
                         d.id >= 0 ? fmt::format(" #{}", d.id) : "", model.links[static_cast<std::size_t>(d.link)].name,
                         d.plugin ? " (plugin, opaque)" : "");
  }
  if (!model.extra_joints.empty()) {
    out += "extra joints:\n";
    for (const ExtraJoint& j : model.extra_joints)
      out += fmt::format("  {} {} - {}\n", j.type, model.links[static_cast<std::size_t>(j.link1)].name,
                         model.links[static_cast<std::size_t>(j.link2)].name);
  }
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
}

std::string format_reference_yaml(const Model& model, const Derived& derived, const std::vector<LinkBounds>& boxes,
                                  const std::vector<Diagnostic>& diagnostics) {
  std::string out = "loaded: true\n";
  out += "model_name: " + quoted(model.name) + "\n";
  out += "total_mass: " + number(derived.total_mass) + "\n";
  out += fmt::format("num_links: {}\n", model.links.size());
  out += fmt::format("num_joints: {}\n", model.num_joints());
  const Link& root = model.root();
  out += "root_translation: " + list(root.X_PL.translation()) + "\n";
  out += "root_rotation: " + matrix(root.X_PL.linear()) + "\n";
  out += "links:\n";
  const std::vector<Eigen::Isometry3d> X_RL = compute_root_relative_frames(model);
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& l = model.links[i];
    const MassProperties& m = derived.mass[i];
    out += "- name: " + quoted(l.name) + "\n";
    out += "  parent: " +
           (l.parent < 0 ? std::string("null") : quoted(model.links[static_cast<std::size_t>(l.parent)].name)) + "\n";
    out += "  joint_type: " + std::string(joint_type_name(l.joint_type)) + "\n";
    out += fmt::format("  joint_id: {}\n", l.joint_id);
    out += "  joint_axis: " + list(l.joint_axis) + "\n";
    out += "  joint_range: " + pair(l.joint_range_lower, l.joint_range_upper) + "\n";
    out += "  joint_velocity_range: " + pair(l.velocity_lower, l.velocity_upper) + "\n";
    out += "  mass: " + number(m.mass) + "\n";
    out += "  center_of_mass: " + list(m.center_of_mass) + "\n";
    out += "  inertia: " + matrix(m.inertia) + "\n";
    if (l.parent >= 0) {
      out += "  translation: " + list(l.X_PL.translation()) + "\n";
      out += "  rotation: " + matrix(l.X_PL.linear()) + "\n";
    }
    out += "  world_translation_at_zero: " + list(X_RL[i].translation()) + "\n";
    if (!boxes[i].visual.empty()) out += "  visual_bbox: " + bbox(boxes[i].visual) + "\n";
    if (!boxes[i].collision.empty()) out += "  collision_bbox: " + bbox(boxes[i].collision) + "\n";
  }
  out += "devices:\n";
  for (const Device& d : model.devices) {
    out += "- name: " + quoted(d.name) + "\n";
    out += "  type: " + d.type + "\n";
    out += "  link: " + quoted(model.links[static_cast<std::size_t>(d.link)].name) + "\n";
    out += "  translation: " + list(d.X_LD.translation()) + "\n";
    out += "  rotation: " + matrix(d.X_LD.linear()) + "\n";
    if (const auto* c = std::get_if<CameraParams>(&d.params)) {
      out += "  field_of_view: " + number(c->field_of_view) + "\n";
      out += fmt::format("  resolution: [{}, {}]\n", c->width, c->height);
      out += "  near_clip_distance: " + number(c->near_clip_distance) + "\n";
      out += "  far_clip_distance: " + number(c->far_clip_distance) + "\n";
    } else if (const auto* l = std::get_if<LightParams>(&d.params); l && d.type == "SpotLight") {
      out += "  direction: " + list(l->direction) + "\n";
      out += "  beam_width: " + number(l->beam_width) + "\n";
      out += "  cut_off_angle: " + number(l->cut_off_angle) + "\n";
      out += "  cut_off_exponent: " + number(l->cut_off_exponent) + "\n";
    }
  }
  out += fmt::format("extra_joints: {}\n", model.extra_joints.size());
  std::string messages;
  for (const Diagnostic& d : diagnostics)
    if (d.severity >= Severity::kWarning) messages += format_diagnostic(d) + "\n";
  out += "messages: " + quoted(messages) + "\n";
  return out;
}

}  // namespace bodyfmt::tools

namespace bodyfmt::tools {

std::string format_pose_yaml(const Model& model, const std::vector<Eigen::Isometry3d>& X_WL) {
  std::string out = "model_name: " + quoted(model.name) + "\nlink_frames:\n";
  for (std::size_t i = 0; i < model.links.size() && i < X_WL.size(); ++i) {
    const Eigen::Vector3d p = X_WL[i].translation();
    const Eigen::Matrix3d R = X_WL[i].linear();
    out += "- name: " + quoted(model.links[i].name) + "\n";
    out += fmt::format("  translation: [{:.17g}, {:.17g}, {:.17g}]\n", p.x(), p.y(), p.z());
    out +=
        fmt::format("  rotation: [{:.17g}, {:.17g}, {:.17g}, {:.17g}, {:.17g}, {:.17g}, {:.17g}, {:.17g}, {:.17g}]\n",
                    R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2));
  }
  return out;
}

}  // namespace bodyfmt::tools
