#pragma once
/// The one post-processing step over what assimp's glTF2 exporter writes (SUPPORT.md,
/// "assimp and the post-processing step"). The writer hands assimp the meshes and materials,
/// named with a marker ("bodyfmt#<index>"), and one empty root node, and keeps the nodes and
/// the real data in SceneTables; finish_gltf() then:
///  * writes the nodes from the tables as assimp writes a node tree (depth-first pre-order),
///    with their transforms in double precision (assimp stores float matrices), link extras,
///    cameras and KHR_lights_punctual lights (assimp 5.2 writes neither);
///  * replaces assimp's materials by the writer's PBR materials, drops unused ones and
///    points primitives at them;
///  * normalises every NORMAL accessor in the binary buffer (assimp writes importer normals
///    as they come, which the validator rejects as ACCESSOR_VECTOR3_NON_UNIT);
///  * lists only the extensions actually used and names bodyfmt as the generator;
///  * appends embedded images to the binary buffer (GLB) or refers to them by URI (.gltf).
#include "json.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::gltf {

inline constexpr std::string_view kMarker = "bodyfmt#";

struct NodeTable {
  static constexpr std::uint32_t kNoParent = UINT32_MAX;
  std::uint32_t parent = kNoParent;  ///< index of the parent node; nodes come after their parent
  int mesh = -1;                     ///< index of the aiMesh the node shows
  std::string name;
  Eigen::Affine3d transform = Eigen::Affine3d::Identity();
  std::string extras;  ///< a JSON object as text (Json::dump); empty = none
  int camera = -1;     ///< index into SceneTables::cameras
  int light = -1;      ///< index into SceneTables::lights
};

struct ImageTable {
  std::string file_name;  ///< for .gltf output, relative to the .gltf file
  std::string mime_type;
  std::string bytes;
};

struct SceneTables {
  std::vector<NodeTable> nodes;
  std::vector<std::string> mesh_names;
  std::vector<Json> materials;
  Json cameras = Json::array();
  Json lights = Json::array();
  Json textures = Json::array();
  Json samplers = Json::array();
  std::vector<ImageTable> images;
  std::string generator;
};

struct FinishedGltf {
  std::string json;
  std::string bin;
};

/// `glb` is assimp's GLB blob. `bin_uri` empty: GLB layout (images in the buffer); else the
/// .gltf layout with the buffer at that URI and images at their file names.
std::optional<FinishedGltf> finish_gltf(std::string_view glb, const SceneTables& tables, const std::string& bin_uri,
                                        std::string* error);

/// Packs JSON and binary chunk into a GLB file (both padded to 4 bytes as the spec asks).
std::string pack_glb(const std::string& json, const std::string& bin);

/// Splits a GLB file into its JSON text and binary chunk; nullopt when it is not one.
std::optional<FinishedGltf> unpack_glb(std::string_view glb);

}  // namespace bodyfmt::gltf
