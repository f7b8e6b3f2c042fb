#pragma once
/// STL, OBJ, COLLADA and glTF through assimp, converted into the format-neutral SceneNode tree.
///
/// This file is built into its own module (libbodyfmt_assimp.so), not into libbodyfmt, so that
/// only processes that import such a mesh pay for loading assimp and its dependencies.
/// libbodyfmt reaches it through mesh/assimp_module.h, which dlopen()s the module and looks up
/// the one extern "C" entry point below.
///
/// The module links assimp but not libbodyfmt: the tools link libbodyfmt statically, and a module
/// that loaded libbodyfmt.so into them would bring a second copy of the library. The few library
/// functions it needs are passed in by the host (AssimpHost).

#include "mesh_import/scene_tree.h"

#include <bodyfmt/diagnostic.h>

#include <string>

namespace bodyfmt::mesh {

/// What the module calls back into libbodyfmt for, filled in by the host (assimp_module.cpp).
struct AssimpHost {
  /// report_rule(sink, rule_id, where, message).
  void (*report)(DiagnosticSink& sink, const char* rule_id, const SourceLocation& where, std::string message);
  /// resolve_relative(base_file, url) of mesh/vrml_reader.h.
  std::string (*resolve_relative)(const std::string& base_file, const std::string& url);
};

/// Reads `path` with assimp. On failure reports `mesh-parse` (with assimp's message) at `where`
/// and returns nullptr.
SceneTree read_with_assimp(const AssimpHost& host, const std::string& path, DiagnosticSink& sink,
                           const SourceLocation& where);

}  // namespace bodyfmt::mesh

/// The module's entry point, looked up by name (kAssimpEntryPoint in assimp_module.cpp) so that
/// dlsym() needs no C++ mangling: it calls read_with_assimp() and stores the result in `*out`.
/// C++ types cross the boundary because the module and libbodyfmt are always built together
/// with the same compiler and standard library. The "_v2" suffix changes if the signature does.
extern "C" void bodyfmt_assimp_read_v2(const bodyfmt::mesh::AssimpHost* host, const char* path,
                                       bodyfmt::DiagnosticSink* sink, const bodyfmt::SourceLocation* where,
                                       bodyfmt::mesh::SceneTree* out);
