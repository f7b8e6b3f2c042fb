#pragma once
// Shape geometry and appearance nodes (body-format-spec §8.6, §8.7, §9).

#include <bodyfmt/model.h>

#include "load/load_context.h"

#include <optional>
#include <string>

namespace bodyfmt::detail {

/// Resolves a resource URI written in `referring_file` to a local path; empty when it cannot.
/// Reports `load-uri` for unsupported schemes and undefined path variables.
std::string resolve_uri(LoadContext& ctx, const yaml::NodeRef& at, const std::string& uri,
                        const std::string& referring_file);

/// Reads `metadata` (length_unit, upper_axis, legacy string form) into `mesh`.
void read_mesh_metadata(LoadContext& ctx, const yaml::NodeRef& metadata, MeshResource& mesh);

/// Reads a `geometry` mapping. `division_number` is set when the node gives one.
std::optional<Geometry> read_geometry(LoadContext& ctx, const yaml::NodeRef& geometry,
                                      int& division_number);

Appearance read_appearance(LoadContext& ctx, const yaml::NodeRef& appearance);

}  // namespace bodyfmt::detail
