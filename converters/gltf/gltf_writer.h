#pragma once
/// body2gltf's writer: Model -> glTF 2.0 (GLB, or .gltf + .bin + texture files). Meshes and
/// materials are built as an aiScene and written by assimp's glTF2 exporter; the nodes are
/// kept in tables, and one post-processing pass over the exported JSON (gltf_finish.h) writes
/// them and makes the file valid and complete. SUPPORT.md lists what maps,
/// what is approximated and what is lost; every loss is reported as `export-loss` at its
/// source line.
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <string>

namespace bodyfmt::gltf {

enum class GeometrySet {
  kVisual,     ///< the visual model (default)
  kCollision,  ///< the collision model instead
  kBoth,       ///< both, under "<link>/visual" and "<link>/collision" nodes; collision hidden
};

struct GltfOptions {
  GeometrySet geometry = GeometrySet::kVisual;
  /// GLB (one binary file) or JSON .gltf with one .bin and the texture files beside it.
  bool binary = true;
  /// Written into asset.generator after "bodyfmt ".
  std::string version = "0";
};

/// Builds the glTF and stages it (and for .gltf its .bin and textures) in `output`. Losses go
/// to `sink` as `export-loss`; an export assimp refuses is reported as `export-write` (fatal)
/// and calls output.fail(). Returns false in that case.
bool write_gltf(const Model& model, const Derived& derived, const GltfOptions& options, converters::OutputSet& output,
                DiagnosticSink& sink);

}  // namespace bodyfmt::gltf
