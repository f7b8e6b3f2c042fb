// Compares two loaded models: the proof that a fixed file describes the same model as the
// original (bodycheck --fix writes nothing otherwise). The fields are the field table's, as
// bodydiff compares them (fields/model_fields.h); what the table does not hold because bodydiff
// pairs by name what a rewrite must keep in place is compared here: the order of links, devices
// and shapes, each mass contribution, scene frames, shape names, texture repeats, mesh assets.

#include <bodyfmt/fix.h>

#include "fields/field_collector.h"
#include "fields/field_text.h"

#include <fmt/format.h>

#include <set>

namespace bodyfmt {
namespace {

using detail::Field;

// The first difference between two lists of fields of the same part of the model.
std::optional<std::string> fields_difference(const std::vector<Field>& a, const std::vector<Field>& b,
                                             const std::string& where, double tolerance) {
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (a[i].key != b[i].key) break;
    if (!detail::same_value(a[i], b[i], tolerance))
      return fmt::format("{}{}: {} != {}", where, a[i].key, detail::field_value(a[i]), detail::field_value(b[i]));
  }
  if (a.size() == b.size()) {
    bool same_keys = true;
    for (std::size_t i = 0; i < a.size() && same_keys; ++i) same_keys = a[i].key == b[i].key;
    if (same_keys) return std::nullopt;
  }
  std::set<std::string_view> keys_a, keys_b;
  for (const Field& f : a) keys_a.insert(f.key);
  for (const Field& f : b) keys_b.insert(f.key);
  for (const Field& f : a)
    if (!keys_b.count(f.key)) return fmt::format("{}{}: in the first model only", where, f.key);
  for (const Field& f : b)
    if (!keys_a.count(f.key)) return fmt::format("{}{}: in the second model only", where, f.key);
  return where + "fields in another order";
}

// What the field table does not hold, compared in place.
class Structure {
 public:
  explicit Structure(double tolerance) : tolerance_(tolerance) {}

  std::optional<std::string> difference;

  template <typename T>
  void equal(const std::string& what, const T& a, const T& b) {
    if (!difference && !(a == b)) difference = what + " differs";
  }
  void numbers(const std::string& what, const double* a, const double* b, std::size_t n) {
    for (std::size_t i = 0; i < n && !difference; ++i)
      if (!detail::same_number(a[i], b[i], tolerance_)) difference = fmt::format("{}: {} != {}", what, a[i], b[i]);
  }
  bool count(const std::string& what, std::size_t a, std::size_t b) {
    if (!difference && a != b) difference = fmt::format("{}: {} != {} entries", what, a, b);
    return !difference;
  }

  void link(const std::string& what, const Link& a, const Link& b) {
    equal(what + " name", a.name, b.name);
    equal(what + " children", a.children, b.children);
    // The table holds a joint's axis and limits where the joint moves (bodydiff's view); the
    // model keeps them for every joint and bodyinfo's reference report shows them all.
    if (a.joint_type == JointType::kFixed || a.joint_type == JointType::kFree) {
      numbers(what + " joint_axis", a.joint_axis.data(), b.joint_axis.data(), 3);
      const double limits_a[] = {a.joint_range_lower,    a.joint_range_upper, a.velocity_lower,
                                 a.velocity_upper,       a.effort_lower,      a.effort_upper,
                                 a.initial_displacement, a.joint_axis_inertia};
      const double limits_b[] = {b.joint_range_lower,    b.joint_range_upper, b.velocity_lower,
                                 b.velocity_upper,       b.effort_lower,      b.effort_upper,
                                 b.initial_displacement, b.joint_axis_inertia};
      numbers(what + " joint limits", limits_a, limits_b, 8);
    }
    // The table holds the combined mass data; a rewrite must also keep each part of it (the
    // link keys and each RigidBody element) where it was.
    if (count(what + " mass contributions", a.mass_contributions.size(), b.mass_contributions.size()))
      for (std::size_t i = 0; i < a.mass_contributions.size() && !difference; ++i) {
        const MassContribution &x = a.mass_contributions[i], &y = b.mass_contributions[i];
        const std::string w = fmt::format("{} mass contribution {}", what, i);
        numbers(w + " mass", &x.mass, &y.mass, 1);
        numbers(w + " center_of_mass", x.center_of_mass.data(), y.center_of_mass.data(), 3);
        numbers(w + " inertia", x.inertia.data(), y.inertia.data(), 9);
        equal(w + " from_link_keys", x.from_link_keys, y.from_link_keys);
      }
    if (count(what + " shapes", a.shapes.size(), b.shapes.size()))
      for (std::size_t i = 0; i < a.shapes.size() && !difference; ++i) {
        const Shape &x = a.shapes[i], &y = b.shapes[i];
        const std::string w = fmt::format("{} shape {}", what, i);
        equal(w + " name", std::string(x.name), std::string(y.name));
        equal(w + " frame", x.frame, y.frame);
        const Texture* tx = x.appearance.texture ? &*x.appearance.texture : nullptr;
        const Texture* ty = y.appearance.texture ? &*y.appearance.texture : nullptr;
        if (tx && ty)
          equal(w + " texture repeat", std::pair(tx->repeat_s, tx->repeat_t), std::pair(ty->repeat_s, ty->repeat_t));
        const MeshResource* mx = geometry_if<MeshResource>(x.geometry);
        const MeshResource* my = geometry_if<MeshResource>(y.geometry);
        if (mx && my) equal(w + " mesh asset", mx->mesh, my->mesh);
      }
    if (count(what + " frames", a.frames.size(), b.frames.size()))
      for (std::size_t i = 0; i < a.frames.size() && !difference; ++i) {
        const std::string w = fmt::format("{} frame {}", what, i);
        equal(w + " parent", a.frames[i].parent, b.frames[i].parent);
        equal(w + " rigid_body", a.frames[i].rigid_body, b.frames[i].rigid_body);
        numbers(w + " placement", a.frames[i].X_PF.data(), b.frames[i].X_PF.data(), 12);
      }
  }

  void model(const Model& a, const Model& b) {
    equal("body_handlers", a.body_handlers, b.body_handlers);
    if (count("links", a.links.size(), b.links.size()))
      for (std::size_t i = 0; i < a.links.size() && !difference; ++i)
        link(fmt::format("link {} \"{}\"", i, a.links[i].name), a.links[i], b.links[i]);
    if (count("devices", a.devices.size(), b.devices.size()))
      for (std::size_t i = 0; i < a.devices.size() && !difference; ++i) {
        const Device &x = a.devices[i], &y = b.devices[i];
        const std::string w = fmt::format("device {} \"{}\"", i, x.name);
        equal(w + " name", x.name, y.name);
        equal(w + " node_type", x.node_type, y.node_type);
        equal(w + " plugin", x.plugin, y.plugin);
        equal(w + " link", x.link, y.link);
      }
    if (count("extra_joints", a.extra_joints.size(), b.extra_joints.size()))
      for (std::size_t i = 0; i < a.extra_joints.size() && !difference; ++i) {
        equal(fmt::format("extra_joint {} link1", i), a.extra_joints[i].link1, b.extra_joints[i].link1);
        equal(fmt::format("extra_joint {} link2", i), a.extra_joints[i].link2, b.extra_joints[i].link2);
      }
    if (count("meshes", a.meshes.size(), b.meshes.size()))
      for (std::size_t i = 0; i < a.meshes.size() && !difference; ++i) {
        const MeshAsset &x = a.meshes[i], &y = b.meshes[i];
        equal(fmt::format("mesh {} path", i), x.path, y.path);
        equal(fmt::format("mesh {} node", i), x.node, y.node);
        count(fmt::format("mesh {} parts", i), x.parts.size(), y.parts.size());
      }
  }

 private:
  double tolerance_;
};

}  // namespace

std::optional<std::string> model_difference(const Model& a, const Model& b, double relative_tolerance) {
  Structure structure(relative_tolerance);
  structure.model(a, b);
  if (structure.difference) return structure.difference;
  // A rewrite must name the same files: mesh and texture URIs and paths, not their bytes.
  detail::FieldCollector fa(a, false, detail::FileKeys::By::kPath);
  detail::FieldCollector fb(b, false, detail::FileKeys::By::kPath);
  if (auto d = fields_difference(fa.model_fields(), fb.model_fields(), "", relative_tolerance)) return d;
  for (std::size_t i = 0; i < a.links.size(); ++i)
    if (auto d = fields_difference(fa.link(i).fields, fb.link(i).fields, fmt::format("link \"{}\" ", a.links[i].name),
                                   relative_tolerance))
      return d;
  return std::nullopt;
}

}  // namespace bodyfmt
