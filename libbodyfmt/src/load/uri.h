#pragma once
// Resource URIs (body-format-spec §9.1) and mesh metadata (§9.4).

#include <bodyfmt/model.h>

#include "load/load_context.h"

#include <string>
#include <vector>

namespace bodyfmt::detail {

/// Resolves a resource URI written in `referring_file` to a local path; empty when it cannot.
/// Relative paths, `file://`, `${HOME}` and `package://NAME/` (bodyfmt/package_map.h, from
/// the referring file's folder). Reports `load-uri` for unsupported schemes, unknown packages and
/// undefined path variables.
std::string resolve_uri(LoadContext& ctx, const yaml::NodeRef& at, const std::string& uri,
                        const std::string& referring_file);

/// The key that identifies a file for include-cycle detection and caching: its canonical path,
/// or, where that cannot be made (a pipe such as /dev/fd/63, a name given for standard
/// input), the absolute, lexically normal path. Never throws.
std::string file_identity(const std::string& path);

/// An include chain for a message, file names only: "a.body -> b.body -> a.body" for the files
/// being read (outermost first) and `last`, the one that closes or would deepen it.
std::string include_chain_text(const std::vector<std::string>& chain, const std::string& last);

/// Reads `metadata` (length_unit, upper_axis, legacy string form) into `mesh`.
void read_mesh_metadata(LoadContext& ctx, const yaml::NodeRef& metadata, MeshResource& mesh);

}  // namespace bodyfmt::detail
