#pragma once
// The loader's side of FileCache: included texts and parsed mesh files by path, each with the
// modification time and size it was read at.
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/file_cache.h>

#include "mesh/scene_tree.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
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

  std::mutex mutex;
  std::map<std::string, Text> texts;
  std::map<std::string, Mesh> meshes;
  int files_read = 0;

  /// The text of an included file, from the cache when unchanged.
  std::optional<std::string> read_text(const std::string& path, std::uintmax_t max_bytes, std::string& why);
};

}  // namespace bodyfmt
