// MeshCache and import_mesh(): file checks, format dispatch by extension, one parse per file,
// and one asset per (file, node, metadata) (body-format-spec §9.2, §9.4).
#include <bodyfmt/mesh_import.h>

#include <bodyfmt/rules.h>
#include "mesh_import/file_cache_impl.h"

#include <bodyfmt/read_file.h>
#include "mesh_import/assimp_module.h"
#include "mesh_import/scene_tree.h"
#include "mesh_import/vrml_reader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace bodyfmt {

namespace {

enum class Format { kVrml, kAssimp, kUnsupported };

Format format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".wrl") return Format::kVrml;
  if (ext == ".stl" || ext == ".obj" || ext == ".dae" || ext == ".gltf" || ext == ".glb") return Format::kAssimp;
  return Format::kUnsupported;
}

void report(DiagnosticSink& sink, const char* rule, const SourceLocation& where, std::string message,
            std::string hint = {}) {
  report_rule(sink, rule, where, std::move(message), std::move(hint));
}

/// The triangle count a binary STL file declares when its size matches it (84 header bytes,
/// then 50 per triangle); 0 for anything else (ASCII STL, other formats, short files).
std::uint32_t binary_stl_triangles(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".stl") return 0;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  unsigned char header[84];
  if (ec || !in.read(reinterpret_cast<char*>(header), sizeof header)) return 0;
  const std::uint32_t count = static_cast<std::uint32_t>(header[80]) | static_cast<std::uint32_t>(header[81]) << 8 |
                              static_cast<std::uint32_t>(header[82]) << 16 |
                              static_cast<std::uint32_t>(header[83]) << 24;
  return size == 84 + 50 * static_cast<std::uintmax_t>(count) ? count : 0;
}

}  // namespace

struct MeshCache::Impl {
  struct FileEntry {
    mesh::SceneTree tree;  // nullptr: failed (already reported)
  };
  using AssetKey = std::tuple<std::string, std::string, double, bool, std::vector<std::string>>;

  std::map<std::string, FileEntry> files;
  std::map<AssetKey, std::shared_ptr<const MeshAsset>> assets;
  std::set<AssetKey> failed_assets;
  std::vector<std::string> inline_stack;  // VRML files being parsed, for Inline cycles
  int parsed = 0;
  std::shared_ptr<FileCache> file_cache;  // across loads (LoadOptions::file_cache), may be null
  std::uintmax_t max_file_bytes = MeshImportOptions{}.max_file_bytes;  // of the import being read
  std::uint32_t max_triangles = MeshImportOptions{}.max_triangles;

  /// Parses `path` once; later calls return the cached tree (or nullptr after a failure).
  mesh::SceneTree load_file(const std::string& path, DiagnosticSink& sink, const SourceLocation& where) {
    if (auto it = files.find(path); it != files.end()) return it->second.tree;
    if (std::find(inline_stack.begin(), inline_stack.end(), path) != inline_stack.end()) {
      report(sink, "mesh-inline-cycle", where, "VRML Inline \"" + path + "\" includes itself");
      return nullptr;
    }
    mesh::SceneTree tree = file_cache ? parse_through_cache(path, sink, where) : parse_file(path, sink, where);
    files[path].tree = tree;
    return tree;
  }

  /// The parts of `key`'s node of `tree` (null when the node is not in it), taken from the file
  /// cache when an earlier load extracted them from the unchanged file.
  std::shared_ptr<const MeshAsset> extract(const mesh::SceneNode& tree, const AssetKey& key) {
    std::optional<FileCache::Impl::Stamp> stamp;
    if (file_cache) {
      stamp = FileCache::Impl::stamp_of(std::get<0>(key));
      std::lock_guard<std::mutex> lock(file_cache->impl().mutex);
      const auto fresh = [&](const FileCache::Impl::Asset& a) { return a.stamp == *stamp; };
      if (stamp)
        if (auto cached = file_cache->impl().assets.find(key, fresh)) return cached->asset;
    }
    auto asset = std::make_shared<MeshAsset>();
    asset->path = std::get<0>(key);
    asset->node = std::get<1>(key);
    std::shared_ptr<const MeshAsset> result = asset;
    if (!mesh::extract_parts(tree, std::get<1>(key), std::get<2>(key), std::get<3>(key), asset->parts, std::get<4>(key),
                             &asset->scene_bounds))
      result = nullptr;
    if (stamp) {
      std::lock_guard<std::mutex> lock(file_cache->impl().mutex);
      file_cache->impl().assets.put(
          key, std::make_shared<const FileCache::Impl::Asset>(FileCache::Impl::Asset{*stamp, result}));
    }
    return result;
  }

  /// parse_file, or the tree an earlier load parsed from the unchanged file, its findings
  /// said again at this load's `where`.
  mesh::SceneTree parse_through_cache(const std::string& path, DiagnosticSink& sink, const SourceLocation& where) {
    FileCache::Impl& cache = file_cache->impl();
    const std::optional<FileCache::Impl::Stamp> stamp = FileCache::Impl::stamp_of(path);
    if (stamp) {
      std::unique_lock<std::mutex> lock(cache.mutex);
      const auto fresh = [&](const FileCache::Impl::Mesh& m) {
        return m.stamp == *stamp && m.max_file_bytes == max_file_bytes && m.max_triangles == max_triangles;
      };
      if (std::shared_ptr<const FileCache::Impl::Mesh> entry = cache.meshes.find(path, fresh)) {
        lock.unlock();
        for (Diagnostic d : entry->reported) {
          if (d.location == entry->where) d.location = where;
          sink.report(std::move(d));
        }
        return entry->tree;
      }
    }
    CollectingSink reported;
    mesh::SceneTree tree = parse_file(path, reported, where);
    for (const Diagnostic& d : reported.diagnostics()) sink.report(d);
    std::lock_guard<std::mutex> lock(cache.mutex);
    ++cache.files_read;
    if (stamp)
      cache.meshes.put(path,
                       std::make_shared<const FileCache::Impl::Mesh>(FileCache::Impl::Mesh{
                           *stamp, max_file_bytes, max_triangles, tree, std::move(reported.diagnostics()), where}));
    return tree;
  }

  mesh::SceneTree parse_file(const std::string& path, DiagnosticSink& sink, const SourceLocation& where) {
    std::error_code ec;
    const Format format = format_of(path);
    if (format == Format::kUnsupported) {
      report(sink, "mesh-format-unsupported", where,
             "the file format of \"" + path + "\" is not supported (use .wrl, .stl, .obj, .dae, .gltf or .glb)");
      return nullptr;
    }
    if (!std::filesystem::exists(path, ec)) {
      report(sink, "mesh-file-missing", where, "mesh file not found: \"" + path + "\"");
      return nullptr;
    }
    std::string why;
    if (!detail::readable_regular_file(path, max_file_bytes, why)) {
      report(sink, "mesh-file-unreadable", where, "cannot read mesh file \"" + path + "\": it " + why);
      return nullptr;
    }
    ++parsed;
    if (format == Format::kAssimp) {
      if (const std::uint32_t triangles = binary_stl_triangles(path); triangles > max_triangles) {
        report(sink, "mesh-too-large", where,
               "mesh file \"" + path + "\" holds " + std::to_string(triangles) + " triangles, more than the limit of " +
                   std::to_string(max_triangles) + " (--max-mesh-triangles); it is not imported",
               "simplify the mesh, or raise --max-mesh-triangles (an import takes about 1.5 KB per triangle)");
        return nullptr;
      }
      return mesh::import_with_assimp(path, max_file_bytes, sink, where);
    }

    const std::optional<std::string> text = detail::read_regular_file(path, max_file_bytes, why);
    if (!text) {
      report(sink, "mesh-file-unreadable", where, "cannot read mesh file \"" + path + "\": " + why);
      return nullptr;
    }
    inline_stack.push_back(path);
    const mesh::InlineLoader loader = [this, &sink](const std::string& inlined, const SourceLocation& at) {
      return load_file(inlined, sink, at);
    };
    mesh::SceneTree tree = mesh::read_vrml(*text, path, sink, loader);
    inline_stack.pop_back();
    return tree;
  }
};

MeshCache::MeshCache() : impl_(std::make_unique<Impl>()) {}
MeshCache::~MeshCache() = default;

int MeshCache::files_parsed() const { return impl_->parsed; }

void MeshCache::use_file_cache(std::shared_ptr<FileCache> cache) { impl_->file_cache = std::move(cache); }

std::shared_ptr<const MeshAsset> MeshCache::get(const std::string& path, const MeshImportOptions& options,
                                                DiagnosticSink& sink, const SourceLocation& where) {
  const std::string normal = std::filesystem::path(path).lexically_normal().string();
  std::vector<std::string> detached = options.detached_nodes;
  std::sort(detached.begin(), detached.end());
  detached.erase(std::unique(detached.begin(), detached.end()), detached.end());
  const Impl::AssetKey key{normal, options.node, options.length_scale, options.y_up, detached};
  if (auto it = impl_->assets.find(key); it != impl_->assets.end()) return it->second;
  if (impl_->failed_assets.count(key)) return nullptr;

  const bool known_file = impl_->files.count(normal) != 0;
  impl_->max_file_bytes = options.max_file_bytes;
  impl_->max_triangles = options.max_triangles;
  mesh::SceneTree tree = impl_->load_file(normal, sink, where);
  if (!tree) {
    impl_->failed_assets.insert(key);
    return nullptr;
  }
  std::shared_ptr<const MeshAsset> asset = impl_->extract(*tree, key);
  if (!asset) {
    report(sink, "mesh-node-not-found", where, "node \"" + options.node + "\" is not found in \"" + normal + "\"",
           "the name must be a VRML DEF name or a node name of the mesh file (first match in depth-first order)");
    impl_->failed_assets.insert(key);
    return nullptr;
  }
  if (asset->parts.empty() && !known_file) {
    report(sink, "mesh-empty", where,
           "mesh file \"" + normal + "\"" + (options.node.empty() ? std::string() : " node \"" + options.node + "\"") +
               " contains no triangles");
  }
  impl_->assets[key] = asset;
  return asset;
}

std::optional<MeshAsset> import_mesh(const std::string& path, const MeshImportOptions& options, DiagnosticSink& sink,
                                     const SourceLocation& where) {
  MeshCache cache;
  auto asset = cache.get(path, options, sink, where);
  if (!asset) return std::nullopt;
  return *asset;
}

}  // namespace bodyfmt
