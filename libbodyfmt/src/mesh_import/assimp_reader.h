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
#include <bodyfmt/read_file.h>

#include <cstdint>
#include <optional>
#include <string>

namespace bodyfmt::mesh {

/// What the module calls back into libbodyfmt for, filled in by the host (assimp_module.cpp).
struct AssimpHost {
  /// report_rule(sink, rule_id, where, message).
  void (*report)(DiagnosticSink& sink, const char* rule_id, const SourceLocation& where, std::string message);
  /// resolve_relative(base_file, url) of mesh/vrml_reader.h.
  std::string (*resolve_relative)(const std::string& base_file, const std::string& url);
  /// read_regular_file_bytes(path, max_bytes, why) of bodyfmt/read_file.h: the one bounded reader.
  std::optional<FileBytes> (*read_file)(const std::string& path, std::uintmax_t max_bytes, std::string& why);
};

/// Reads `path` with assimp. Every file assimp opens (the mesh file and the files it names: an
/// OBJ's material library, a glTF's buffers) is read through host.read_file within
/// `max_file_bytes`; a named file outside the mesh file's folder (absolute, `..`, a symbolic
/// link out of it) is refused with `mesh-reference-outside`, one that is not a readable regular
/// file with `mesh-file-unreadable`, and a non-finite vertex or node transform is
/// `mesh-vertex-not-finite`; in each case the mesh is not used (nullptr). On any other failure
/// reports `mesh-parse` (with assimp's message) at `where` and returns nullptr.
SceneTree read_with_assimp(const AssimpHost& host, const std::string& path, std::uintmax_t max_file_bytes,
                           DiagnosticSink& sink, const SourceLocation& where);

}  // namespace bodyfmt::mesh

/// The module's entry point, looked up by name (kAssimpEntryPoint in assimp_module.cpp) so that
/// dlsym() needs no C++ mangling: it calls read_with_assimp() and stores the result in `*out`.
/// C++ types cross the boundary because the module and libbodyfmt are always built together
/// with the same compiler and standard library. The "_v3" suffix changes if the signature (or
/// AssimpHost) does.
extern "C" void bodyfmt_assimp_read_v3(const bodyfmt::mesh::AssimpHost* host, const char* path,
                                       std::uintmax_t max_file_bytes, bodyfmt::DiagnosticSink* sink,
                                       const bodyfmt::SourceLocation* where, bodyfmt::mesh::SceneTree* out);
