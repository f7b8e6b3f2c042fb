#pragma once
// The loader's side of FileCache: included texts and parsed mesh files by path, each with the
// modification time and size it was read at.
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/file_cache.h>
#include <bodyfmt/model.h>

#include "mesh_import/scene_tree.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace bodyfmt {

struct FileCache::Impl {
  struct Stamp {
    std::filesystem::file_time_type time;
    std::uintmax_t size = 0;
    friend bool operator==(const Stamp& a, const Stamp& b) { return a.time == b.time && a.size == b.size; }
  };
  /// The stamp of a regular file; nullopt for anything else (never cached).
  static std::optional<Stamp> stamp_of(const std::string& path);

  struct Text {
    Stamp stamp;
    std::string text;
  };
  struct Mesh {
    Stamp stamp;
    std::uintmax_t max_file_bytes = 0;
    std::uint32_t max_triangles = 0;
    mesh::SceneTree tree;
    std::vector<Diagnostic> reported;  ///< what parsing it reported
    SourceLocation where;              ///< the `uri:` it was reported at
  };

  /// The parts of one (file, node, metadata) of a parsed file: null when the node is not in it.
  struct Asset {
    Stamp stamp;
    std::shared_ptr<const MeshAsset> asset;
  };
  /// (file, node, length scale, Y up, detached nodes), as MeshCache keys its assets.
  using AssetKey = std::tuple<std::string, std::string, double, bool, std::vector<std::string>>;

  std::mutex mutex;
  std::map<std::string, Text> texts;
  std::map<std::string, Mesh> meshes;
  std::map<AssetKey, Asset> assets;
  int files_read = 0;

  /// The text of an included file, from the cache when unchanged.
  std::optional<std::string> read_text(const std::string& path, std::uintmax_t max_bytes, std::string& why);
};

}  // namespace bodyfmt
