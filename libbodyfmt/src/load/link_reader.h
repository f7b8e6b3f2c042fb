#pragma once
// Link nodes of `links` (body-format-spec §6): joint, offset and link-level mass keys, then
// the element tree.

#include <bodyfmt/model.h>

#include "load/elements.h"
#include "load/mapping_reader.h"

namespace bodyfmt::detail {

struct LinkEntry {
  std::string parent_name;
  /// Where the parent is named (its alias use site, if any). A copy: the link's YAML may be
  /// gone by the time the tree is built (links are read while the file is parsed).
  SourceLocation parent_site;
  /// Where the parent's name is written byte for byte, when a fix-it may edit it there (not
  /// through an alias, which other uses share).
  yaml::TextSpan parent_span;
  /// A second name of the link: a ContinuousTrack's own NAME, which Choreonoid's link map
  /// holds for the first link NAME0 as well (a parent or root_link may name it). Empty if none.
  std::string alias;
  SourceLocation alias_site;
};

/// Reads one link mapping, appending the link to `model.links` (in file order) and its
/// devices to `model.devices`. Returns the parent's name as written.
/// `extra_keys` are keys of composite nodes (ContinuousTrack) read by the caller.
LinkEntry read_link(LoadContext& ctx, const yaml::NodeRef& node, Model& model, ResourceHandler* resources,
                    const std::vector<std::string_view>& extra_keys = {});

/// Applies the link-level keys of a SubBody node to the included root link (body-format-spec
/// §11.2): offset, joint keys (range, velocity and rotor inertia reset when absent),
/// material and extra shapes. Mass keys and RigidBody elements are ignored, with a warning.
void apply_subbody_overrides(LoadContext& ctx, MappingReader& r, Model& model, LinkIndex root,
                             ResourceHandler* resources);

}  // namespace bodyfmt::detail
