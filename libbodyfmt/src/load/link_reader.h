#pragma once
// Link nodes of `links` (body-format-spec §6): joint, offset and link-level mass keys, then
// the element tree.

#include <bodyfmt/model.h>

#include "load/elements.h"

namespace bodyfmt::detail {

struct LinkEntry {
  std::string parent_name;
  yaml::NodeRef parent_ref;
};

/// Reads one link mapping, appending the link to `model.links` (in file order) and its
/// devices to `model.devices`. Returns the parent's name as written.
LinkEntry read_link(LoadContext& ctx, const yaml::NodeRef& node, Model& model, ResourceHandler* resources);

}  // namespace bodyfmt::detail
