#pragma once
/// STL, OBJ, COLLADA and glTF through assimp, converted into the format-neutral SceneNode tree.

#include "mesh/scene_tree.h"

#include <bodyfmt/diagnostic.h>

#include <string>

namespace bodyfmt::mesh {

/// Reads `path` with assimp. On failure reports `mesh-parse` (with assimp's message) at `where`
/// and returns nullptr.
SceneTree read_with_assimp(const std::string& path, DiagnosticSink& sink, const SourceLocation& where);

}  // namespace bodyfmt::mesh
