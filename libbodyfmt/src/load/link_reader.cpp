#include "load/link_reader.h"

#include <bodyfmt/body_keys.h>

#include "load/mapping_reader.h"
#include "load/scalar.h"
#include "load/unit_checks.h"
#include "load/values.h"

namespace bodyfmt::detail {
namespace {

std::optional<JointType> parse_joint_type(std::string_view s) {
  if (s == "fixed") return JointType::kFixed;
  if (s == "free") return JointType::kFree;
  if (s == "revolute") return JointType::kRevolute;
  if (s == "prismatic" || s == "slide") return JointType::kPrismatic;
  if (s == "pseudo_continuous_track" || s == "pseudoContinuousTrack") return JointType::kPseudoContinuousTrack;
  return std::nullopt;
}

void read_joint(LoadContext& ctx, MappingReader& r, Link& link) {
  if (auto t = r.take({"joint_type", "jointType"})) {
    link.sources.set(LinkSources::kJointType, t.use_site());
    if (auto type = parse_joint_type(t->scalar())) {
      link.joint_type = *type;
      if (t->scalar() == "slide" || t->scalar() == "pseudoContinuousTrack") {
        std::vector<FixIt> fixes;
        if (auto fix = edit_value(*t, std::string(joint_type_name(*type)), FixSafety::kSafe))
          fixes.push_back(std::move(*fix));
        ctx.report("load-legacy-key", t, "legacy joint type \"" + std::string(t->scalar()) + "\"",
                   std::string("write ") + std::string(joint_type_name(*type)), std::move(fixes));
      }
    } else {
      std::string hint;
      if (t->scalar() == "continuous" || t->scalar() == "hinge")
        hint = "use revolute (with joint_range: unlimited for a continuous joint)";
      ctx.report("load-joint-type", t, "illegal joint type \"" + std::string(t->scalar()) + "\"", hint);
    }
  }
  if (auto mode = r.take({"actuation_mode", "actuationMode"})) {
    static const std::vector<std::string_view> kModes = {"joint_effort",  "jointEffort",        "jointTorque",
                                                         "jointForce",    "joint_displacement", "jointDisplacement",
                                                         "jointAngle",    "joint_velocity",     "jointVelocity",
                                                         "link_position", "linkPosition",       "jointSurfaceVelocity"};
    link.actuation_mode = mode->scalar();
    if (mode->scalar() == "jointSurfaceVelocity") {
      // body-format-spec §6.3: the deprecated mode turns the joint into a pseudo track.
      link.joint_type = JointType::kPseudoContinuousTrack;
      ctx.report("load-legacy-key", mode, "actuation mode \"jointSurfaceVelocity\" is deprecated",
                 "write joint_type: pseudo_continuous_track");
    } else if (std::find(kModes.begin(), kModes.end(), mode->scalar()) == kModes.end()) {
      ctx.report("load-actuation-mode", mode, "illegal actuation mode \"" + std::string(mode->scalar()) + "\"");
    }
  }
  const bool revolute = link.joint_type == JointType::kRevolute;
  if (auto axis = r.take({"joint_axis", "jointAxis"})) {
    link.sources.set(LinkSources::kJointAxis, axis.use_site());
    if (auto a = read_joint_axis(ctx, axis)) link.joint_axis = *a;
  }
  if (auto id = r.take({"joint_id", "jointId"})) {
    link.sources.set(LinkSources::kJointId, id.use_site());
    if (auto v = required_int(ctx, id)) link.joint_id = *v < 0 ? -1 : static_cast<int>(*v);
  }
  // joint_displacement wins over joint_angle; joint_angle is always an angle (§3). Choreonoid
  // reads joint_angle first in any case (toDouble), so a joint_angle that is no number refuses
  // the file even where joint_displacement replaces it.
  yaml::NodeRef angle = r.take({"joint_angle", "jointAngle"});
  yaml::NodeRef displacement = r.take({"joint_displacement", "jointDisplacement"});
  if (displacement) {
    if (auto v = required_double(ctx, displacement))
      link.initial_displacement = revolute ? ctx.angle(*v, displacement) : *v;
    if (angle) required_double(ctx, angle);  // read (a non-number refuses the file), then replaced
  } else if (angle) {
    if (auto v = required_double(ctx, angle)) {
      link.initial_displacement = ctx.angle(*v, angle);
      if (link.joint_type == JointType::kPrismatic && ctx.degrees)
        ctx.report("load-angle-on-prismatic", angle,
                   "joint_angle on a prismatic joint is converted from degrees by Choreonoid",
                   "use joint_displacement for a prismatic joint");
    }
  }
  if (auto range = r.take({"joint_range", "jointRange"})) {
    link.sources.set(LinkSources::kJointRange, range.use_site());
    if (auto v = read_range(ctx, range, revolute)) {
      std::tie(link.joint_range_lower, link.joint_range_upper) = *v;
      check_degree_range(ctx, link, range, v->first, v->second);
    }
  }
  yaml::NodeRef max_velocity = r.take({"max_joint_velocity", "maxJointVelocity"});
  yaml::NodeRef velocity_range = r.take({"joint_velocity_range", "jointVelocityRange"});
  if (max_velocity) {
    link.sources.set(LinkSources::kJointVelocity, max_velocity.use_site());
    if (auto v = read_symmetric_limit(ctx, max_velocity, revolute)) {
      std::tie(link.velocity_lower, link.velocity_upper) = *v;
      check_degree_velocity(ctx, link, max_velocity, v->first, v->second);
    }
    if (velocity_range)
      ctx.report("load-ignored-key", velocity_range,
                 "joint_velocity_range is ignored by Choreonoid when max_joint_velocity is given");
  } else if (velocity_range) {
    link.sources.set(LinkSources::kJointVelocity, velocity_range.use_site());
    if (auto v = read_velocity_range(ctx, velocity_range, revolute)) {
      std::tie(link.velocity_lower, link.velocity_upper) = *v;
      check_degree_velocity(ctx, link, velocity_range, v->first, v->second);
    }
  }
  if (auto effort = r.take({"max_joint_effort"})) {
    if (auto v = read_symmetric_limit(ctx, effort, false)) std::tie(link.effort_lower, link.effort_upper) = *v;
  }
  yaml::NodeRef axis_inertia = r.take({"joint_axis_inertia"});
  yaml::NodeRef rotor_inertia = r.take({"rotor_inertia", "rotorInertia"});
  yaml::NodeRef gear_ratio = r.take({"gear_ratio", "gearRatio"});
  if (axis_inertia) {
    link.joint_axis_inertia = required_double(ctx, axis_inertia).value_or(0);
  } else if (rotor_inertia || gear_ratio) {
    // Unlike joint_axis_inertia (toDouble, a prefix), Choreonoid reads these two whole, with
    // defaults: a value that is not a number is ignored (no rotor inertia, no gear factor).
    double rotor = rotor_inertia ? optional_double(ctx, rotor_inertia).value_or(0) : 0;
    double gear = gear_ratio ? optional_double(ctx, gear_ratio).value_or(1) : 1;
    link.joint_axis_inertia = gear * gear * rotor;
  }
}

// body-format-spec §6.4 rule 2: link-level keys form one more contribution, whose missing
// keys default to the Link defaults only when there is no RigidBody contribution.
void read_link_mass(LoadContext& ctx, MappingReader& r, Link& link, bool has_rigid_bodies) {
  yaml::NodeRef com = r.take({"center_of_mass", "centerOfMass"});
  yaml::NodeRef mass = r.take({"mass"});
  yaml::NodeRef inertia = r.take({"inertia"});
  if (!com && !mass && !inertia) return;
  MassContribution c;
  c.from_link_keys = true;
  // Keys left out take Choreonoid's defaults, unless RigidBody nodes carry the mass (§6.4).
  if (!has_rigid_bodies) {
    const MassProperties defaults;
    c.mass = defaults.mass;
    c.inertia = defaults.inertia;
  }
  if (com) {
    link.sources.set(LinkSources::kCenterOfMass, com.use_site());
    if (auto v = read_vec3(ctx, com)) c.center_of_mass = *v;
  }
  if (mass) {
    link.sources.set(LinkSources::kMass, mass.use_site());
    if (auto v = required_double(ctx, mass)) c.mass = *v;
  }
  if (inertia) {
    link.sources.set(LinkSources::kInertia, inertia.use_site());
    if (inertia->is_sequence()) {
      if (auto v = read_inertia(ctx, inertia))
        c.inertia = *v;
      else
        c.inertia_refused = true;
    } else {
      ctx.report("load-ignored-value", inertia, "a link-level inertia that is not a sequence is ignored by Choreonoid");
    }
  }
  c.source = (mass ? mass : (inertia ? inertia : com)).use_site();
  link.mass_contributions.push_back(c);
}

}  // namespace

LinkEntry read_link(LoadContext& ctx, const yaml::NodeRef& node, Model& model, ResourceHandler* resources,
                    const std::vector<std::string_view>& extra_keys) {
  LinkEntry entry;
  MappingReader r(ctx, node, "link");
  r.take({"type"});
  for (std::string_view key : extra_keys) r.ignore(key);
  model.links.emplace_back();
  const LinkIndex index = static_cast<LinkIndex>(model.links.size()) - 1;
  auto link = [&]() -> Link& { return model.links[static_cast<std::size_t>(index)]; };
  link().source = node.use_site();
  if (auto name = r.take({"name"})) {
    link().sources.set(LinkSources::kName, name.use_site());
    link().name = required_string(ctx, name).value_or("");
  } else {
    ctx.report("load-link-name", node, "this link has no name", "add name: LINK_NAME");
  }
  if (auto parent = r.take({"parent"})) {
    link().sources.set(LinkSources::kParent, parent.use_site());
    entry.parent_name = required_string(ctx, parent).value_or("");
    entry.parent_site = parent.use_site();
    if (!parent.alias_site && !parent.enclosing_alias) entry.parent_span = parent->span;
  }
  if (auto joint_name = r.take({"joint_name"})) link().joint_name = joint_name->scalar();
  if (auto t = r.take({"translation"})) {
    link().sources.set(LinkSources::kTranslation, t.use_site());
    if (auto v = read_translation(ctx, t)) link().X_PL.translation() = *v;
  }
  if (auto rot = r.take({"rotation"})) {
    link().sources.set(LinkSources::kRotation, rot.use_site());
    if (auto R = read_rotation(ctx, rot)) link().X_PL.linear() = *R;
  }
  read_joint(ctx, r, link());
  if (auto material = r.take({"material"})) link().contact_material = material->scalar();
  if (auto import = r.take({"import"})) {
    // body-format-spec §6.5: import only adds info keys; model keys in it have no effect.
    ctx.report("load-import", import, "import only adds info keys; model keys inside it are ignored by Choreonoid");
    if (import->is_sequence())  // Choreonoid: importList[i].toMapping(), which throws
      for (const yaml::NodeRef& item : import->items())
        if (!item->is_mapping()) ctx.report("load-type", import.child(item), "an import list item must be a mapping");
  }
  ElementReader elements(ctx, model, index, resources);
  elements.read_elements(r.take({"elements"}), ElementFrame{});
  read_link_mass(ctx, r, link(), elements.has_rigid_body());
  if (link().mass_contributions.empty()) {
    // body-format-spec §6.4 rule 4: Choreonoid simulates these defaults; other engines differ.
    ctx.report("load-default-mass", node,
               "link \"" + link().name + "\" has no mass data; Choreonoid uses 1 kg with identity inertia",
               "add mass, center_of_mass and inertia");
  }
  r.report_unknown(body_key_names("link"));
  return entry;
}

void apply_subbody_overrides(LoadContext& ctx, MappingReader& r, Model& model, LinkIndex root,
                             ResourceHandler* resources) {
  Link& link = model.links[static_cast<std::size_t>(root)];
  if (auto t = r.take({"translation"})) {
    link.sources.set(LinkSources::kTranslation, t.use_site());
    if (auto v = read_translation(ctx, t)) link.X_PL.translation() = *v;
  }
  if (auto rot = r.take({"rotation"})) {
    link.sources.set(LinkSources::kRotation, rot.use_site());
    if (auto R = read_rotation(ctx, rot)) link.X_PL.linear() = *R;
  }
  // body-format-spec §11.2: the override re-applies the range, velocity and rotor inertia
  // defaults even when the SubBody node does not mention them.
  link.joint_range_lower = link.velocity_lower = -kUnlimited;
  link.joint_range_upper = link.velocity_upper = kUnlimited;
  link.joint_axis_inertia = 0;
  read_joint(ctx, r, link);
  if (auto material = r.take({"material"})) link.contact_material = material->scalar();
  for (KeyNames names : {KeyNames{"mass"}, KeyNames{"center_of_mass", "centerOfMass"}, KeyNames{"inertia"}}) {
    if (auto ignored = r.take(names))
      ctx.report("load-mass-ignored", ignored, "mass properties on a SubBody node are ignored by Choreonoid");
  }
  const std::size_t contributions = link.mass_contributions.size();
  ElementReader elements(ctx, model, root, resources);
  elements.read_elements(r.take({"elements"}), ElementFrame{});
  Link& after = model.links[static_cast<std::size_t>(root)];
  if (after.mass_contributions.size() != contributions) {
    ctx.report("load-mass-ignored", after.mass_contributions[contributions].source,
               "RigidBody nodes of a SubBody node are ignored by Choreonoid");
    after.mass_contributions.resize(contributions);
    // Their shapes stay, as plain shapes: no ignored RigidBody stands for them.
    for (SceneFrame& f : after.frames)
      if (f.rigid_body >= static_cast<int>(contributions)) f.rigid_body = -1;
  }
}

}  // namespace bodyfmt::detail
