#pragma once
// The loader's side of FileCache: included texts, parsed mesh files and their parts, each with
// the modification time and size it was read at. The caches that share (make_sharing) find each
// other's entries through one Store that holds them weakly; each cache holds, strongly, the
// entries it used, so an entry lives while a cache uses it and no longer.
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/file_cache.h>
#include <bodyfmt/model.h>

#include "mesh_import/scene_tree.h"

#include <cstdint>
#include <filesystem>
#include <functional>
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

  /// One kind of entry: found in this cache, or in another that shares the store.
  template <class Key, class Entry>
  struct Shelf {
    struct Held {
      std::shared_ptr<const Entry> entry;
      bool used = true;  ///< by a load since the last forget_unused
    };
    std::map<Key, std::weak_ptr<const Entry>>* shared = nullptr;  ///< the store's, under its mutex
    std::map<Key, Held> held;

    /// The entry of `key` that `fresh` accepts, now held and marked used; null when none is.
    std::shared_ptr<const Entry> find(const Key& key, const std::function<bool(const Entry&)>& fresh) {
      if (auto it = held.find(key); it != held.end() && fresh(*it->second.entry)) {
        it->second.used = true;
        return it->second.entry;
      }
      auto it = shared->find(key);
      std::shared_ptr<const Entry> entry = it == shared->end() ? nullptr : it->second.lock();
      if (!entry || !fresh(*entry)) return nullptr;
      held[key] = Held{entry, true};
      return entry;
    }
    void put(const Key& key, std::shared_ptr<const Entry> entry) {
      (*shared)[key] = entry;
      held[key] = Held{std::move(entry), true};
    }
    void forget_unused() {
      for (auto it = held.begin(); it != held.end();) {
        if (it->second.used)
          (it++)->second.used = false;
        else
          it = held.erase(it);
      }
      for (auto it = shared->begin(); it != shared->end();) it = it->second.expired() ? shared->erase(it) : ++it;
    }
  };

  /// What the caches that share have in common: their lock, and every entry any of them holds.
  struct Store {
    std::mutex mutex;
    std::map<std::string, std::weak_ptr<const Text>> texts;
    std::map<std::string, std::weak_ptr<const Mesh>> meshes;
    std::map<AssetKey, std::weak_ptr<const Asset>> assets;
  };

  explicit Impl(std::shared_ptr<Store> shared_store);
  ~Impl();

  std::shared_ptr<Store> store;
  std::mutex& mutex;  ///< the store's: guards the shelves below and files_read
  Shelf<std::string, Text> texts;
  Shelf<std::string, Mesh> meshes;
  Shelf<AssetKey, Asset> assets;
  int files_read = 0;

  /// The text of an included file, from the cache when unchanged.
  std::optional<std::string> read_text(const std::string& path, std::uintmax_t max_bytes, std::string& why);
};

}  // namespace bodyfmt
