#include "mass_action.h"

#include <bodyfmt/geometry_fix.h>
#include <bodyfmt/geometry_mass.h>
#include <bodyfmt/readable_number.h>

#include <fmt/format.h>

namespace bodyfmt::lsp {

std::optional<MassFromShapes> mass_from_shapes(const Model& model, const std::string& path, const std::string& text,
                                               const std::vector<Diagnostic>& findings, int line) {
  // Links are in tree order, not in the order of the text: the one written last before the line.
  const Link* at = nullptr;
  std::size_t index = 0;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    if (link.source.file != path || !link.source.known() || link.source.line > line) continue;
    if (!at || link.source.line > at->source.line) {
      at = &link;
      index = i;
    }
  }
  if (!at) return std::nullopt;
  const Link& link = *at;
  MassFromShapes action;
  action.flagged = links_for_geometry_fix(model, findings)[index];
  CollectingSink shapes;  // a shape that is no solid is counted in left_out; the check reports it
  const LinkGeometryMass geometry = link_geometry_mass(model, link, shapes);
  const std::optional<GeometryAtWrittenMass> keys = geometry_at_written_mass(link, geometry);
  action.title = fmt::format("Compute the centre of mass and inertia of link \"{}\" from its shapes", link.name);
  // Every part of the link's mass data, as --fix=geometry writes it: the link-level keys from the
  // shapes below no RigidBody element, each RigidBody element from the shapes below it.
  if (geometry.empty() && geometry.rigid_bodies.empty()) {
    action.unavailable =
        fmt::format("link \"{}\" has no solid {} geometry", link.name, geometry.from_visual ? "visual" : "collision");
  } else if (geometry.left_out > 0) {
    // A tensor from some of the shapes would be wrong without a word: none at all.
    action.unavailable = fmt::format("{} of the link's shapes {} no solid (see mass-geometry-not-solid)",
                                     geometry.left_out, geometry.left_out == 1 ? "is" : "are");
  } else if (!keys) {
    action.unavailable =
        "neither the link nor a RigidBody element with shapes has a mass key (the density would be a "
        "guess)";
  } else if (link.sources.mass().known() && link.sources.mass().file != path) {
    action.unavailable = "its mass keys are written in another file: \"" + link.sources.mass().file.str() + "\"";
  } else {
    action.title += " (mass " + readable_number(keys->combined.mass) + " kg kept)";
    std::string why;
    if (keys->link_keys) {
      std::vector<FixIt> fixes = link_mass_fixes(text, path, link, *keys->link_keys, why);
      if (fixes.empty()) action.unavailable = why;
      action.fixes.insert(action.fixes.end(), fixes.begin(), fixes.end());
    }
    for (const RecomputedRigidBody& body : keys->rigid_bodies) {
      if (!action.unavailable.empty()) break;
      std::vector<FixIt> fixes = rigid_body_mass_fixes(text, path, link, body.contribution, body.as_written, why);
      if (fixes.empty()) action.unavailable = why;
      action.fixes.insert(action.fixes.end(), fixes.begin(), fixes.end());
    }
    // One part that cannot be written would leave the others recomputed alone: all or nothing.
    if (!action.unavailable.empty()) action.fixes.clear();
  }
  return action;
}

}  // namespace bodyfmt::lsp
