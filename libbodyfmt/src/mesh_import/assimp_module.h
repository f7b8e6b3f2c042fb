#pragma once
/// Loads the assimp import module (libbodyfmt_assimp.so, mesh/assimp_reader.cpp) on first use.
/// libbodyfmt does not link assimp: mapping and relocating assimp and its dependencies (draco,
/// minizip, zlib) cost every process about 3.4 ms at start-up (an empty program linked with
/// -lassimp: 4.8 ms against 1.4 ms), even those that never import an STL, OBJ, COLLADA or glTF.

#include "mesh_import/scene_tree.h"

#include <bodyfmt/diagnostic.h>

#include <cstdint>
#include <string>

namespace bodyfmt::mesh {

/// Reads `path` with assimp through the module, loading it on the first call (thread-safe).
/// When the module cannot be loaded, reports `mesh-importer-unavailable` at `where` (with the
/// path tried and the loader's message) and returns nullptr; otherwise as read_with_assimp(), every
/// file it opens limited to `max_file_bytes`.
SceneTree import_with_assimp(const std::string& path, std::uintmax_t max_file_bytes, DiagnosticSink& sink,
                             const SourceLocation& where);

}  // namespace bodyfmt::mesh
