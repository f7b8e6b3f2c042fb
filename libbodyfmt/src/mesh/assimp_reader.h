#pragma once
/// STL, OBJ, COLLADA and glTF through assimp, converted into the format-neutral SceneNode tree.
///
/// This file is built into its own module (libbodyfmt_assimp.so), not into libbodyfmt, so that
/// only processes that import such a mesh pay for loading assimp and its dependencies.
/// libbodyfmt reaches it through mesh/assimp_module.h, which dlopen()s the module and looks up
/// the one extern "C" entry point below.

#include "mesh/scene_tree.h"

#include <bodyfmt/diagnostic.h>

#include <string>

namespace bodyfmt::mesh {

/// Reads `path` with assimp. On failure reports `mesh-parse` (with assimp's message) at `where`
/// and returns nullptr.
SceneTree read_with_assimp(const std::string& path, DiagnosticSink& sink, const SourceLocation& where);

}  // namespace bodyfmt::mesh

/// The module's entry point, looked up by name (kAssimpEntryPoint in assimp_module.cpp) so that
/// dlsym() needs no C++ mangling: it calls read_with_assimp() and stores the result in `*out`.
/// C++ types cross the boundary because the module and libbodyfmt are always built together
/// with the same compiler and standard library. The "_v1" suffix changes if the signature does.
extern "C" void bodyfmt_assimp_read_v1(const char* path, bodyfmt::DiagnosticSink* sink,
                                       const bodyfmt::SourceLocation* where, bodyfmt::mesh::SceneTree* out);
