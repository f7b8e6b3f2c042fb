#pragma once
/// Writing triangle meshes to files other tools read, deterministically (the same mesh gives
/// the same bytes).
#include <bodyfmt/mesh.h>

#include <optional>
#include <string>
#include <string_view>

namespace bodyfmt::converters {

enum class MeshFormat { kStl, kDae };

/// "stl" or "dae".
std::string_view mesh_format_extension(MeshFormat format);

/// Binary STL: fixed 80-byte header, facet normals from the triangles, float32 little-endian.
std::string write_stl(const TriangleMesh& mesh);

/// COLLADA 1.4 through assimp's exporter, with the material's diffuse colour and
/// transparency when given. assimp's <created>/<modified> timestamps are replaced by a fixed
/// date so that the output is deterministic. Returns nullopt (and sets `error`) when assimp
/// fails.
std::optional<std::string> write_dae(const TriangleMesh& mesh, const std::optional<Material>& material,
                                     std::string_view name, std::string& error);

/// write_stl or write_dae.
std::optional<std::string> write_mesh(MeshFormat format, const TriangleMesh& mesh,
                                      const std::optional<Material>& material, std::string_view name,
                                      std::string& error);

}  // namespace bodyfmt::converters
