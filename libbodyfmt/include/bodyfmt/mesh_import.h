#pragma once
/// Importing external mesh files (Resource nodes, body-format-spec §8.5, §9.2, §9.4) into
/// triangle meshes in the resource frame.
///
/// Formats by extension, case-insensitive: `.wrl` (VRML97, our own reader: see
/// src/mesh_import/VRML_READER.md), and through assimp `.stl`, `.obj`, `.dae`, `.gltf`, `.glb`.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

struct MeshImportOptions {
  /// `node` / `fragment`: the first scene node of this name in depth-first order (VRML DEF
  /// name, assimp node or mesh name); empty = the whole file.
  std::string node;
  /// metadata `length_unit`: multiplies positions (0.001 millimetre, 0.0254 inch).
  double length_scale = 1.0;
  /// metadata `upper_axis: Y`: mesh +Y becomes +Z, +X becomes +Y, +Z becomes +X.
  bool y_up = false;
  /// Nodes of the same file that other Resource references of the body select. Choreonoid
  /// detaches each selected node from the file's shared scene, so in the end no reference
  /// shows them twice: link TURRET_Y of TankBody.body (node TURRET_Y, a Transform whose
  /// children include the TURRET_P Transform) has a reference visual_bbox without TURRET_P.
  /// Pass every node name the body selects from this file; the selected node itself is
  /// never dropped. Empty = the whole subtree (what a single reference sees).
  std::vector<std::string> detached_nodes;
  /// Largest mesh file read (LoadOptions::max_file_bytes); only regular files are read.
  std::uintmax_t max_file_bytes = 256u << 20;
  /// Most triangles of a binary STL file (LoadOptions::max_mesh_triangles), found from its
  /// header before it is imported.
  std::uint32_t max_triangles = 1'000'000;
};

/// Reads a mesh file into parts in the resource frame (metres, Z-up after metadata).
/// With `options.node`, selects the first node of that name in depth-first order and
/// re-centres it per body-format-spec §9.4 (the translations of its ancestors and its own are
/// dropped; the accumulated rotation and scale are kept).
///
/// Reports located diagnostics (`mesh-file-missing`, `mesh-file-unreadable`,
/// `mesh-format-unsupported`, `mesh-parse`, `mesh-node-not-found`, `mesh-inline-cycle`,
/// `mesh-invalid-geometry`, `mesh-empty`) and returns nullopt when nothing usable was read.
/// `where` is the location of the reference (the Resource node); errors inside the mesh file
/// are located in the mesh file itself.
std::optional<MeshAsset> import_mesh(const std::string& path, const MeshImportOptions& options, DiagnosticSink& sink,
                                     const SourceLocation& where);

/// Parses each mesh file once per run and hands out one shared asset per
/// (file, node, metadata), as Choreonoid does (body-format-spec §9.2 "Each (uri, metadata)
/// pair is loaded once and shared").
///
/// Failures are cached too: a file that cannot be read is reported on the first request
/// only, and a missing node once per (file, node).
class FileCache;

class MeshCache {
 public:
  MeshCache();
  ~MeshCache();
  MeshCache(const MeshCache&) = delete;
  MeshCache& operator=(const MeshCache&) = delete;

  /// Same contract as import_mesh(); nullptr when nothing usable was read.
  std::shared_ptr<const MeshAsset> get(const std::string& path, const MeshImportOptions& options, DiagnosticSink& sink,
                                       const SourceLocation& where);

  /// How many files were actually parsed (including inlined VRML files and failures).
  int files_parsed() const;

  /// Takes parsed files from `cache` (and keeps them there) while they are unchanged on disk.
  void use_file_cache(std::shared_ptr<FileCache> cache);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bodyfmt
#pragma GCC visibility pop
