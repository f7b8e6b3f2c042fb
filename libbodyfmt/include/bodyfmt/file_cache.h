#pragma once
/// Files read by earlier loads, kept while their modification time and size stay the same
/// (LoadOptions::file_cache): a language server loads a model at every keystroke, and must
/// re-read only its buffer, not parse its meshes or read its included files each time. The
/// findings of a load are the same with or without it: a mesh file's findings are replayed at
/// the `uri:` that names it in the new load. Safe to share between threads.
///
/// A cache keeps every file it read until forget_unused() is called. Caches made to share with
/// another (one per open document, say) read each file once between them, and a file stays in
/// memory while any of them still uses it: closing a document (dropping its cache) frees what
/// only it used.
#include <bodyfmt/export.h>

#include <cstddef>
#include <memory>

#pragma GCC visibility push(default)
namespace bodyfmt {

class FileCache {
 public:
  FileCache();
  ~FileCache();
  FileCache(const FileCache&) = delete;
  FileCache& operator=(const FileCache&) = delete;

  /// A new, empty cache that shares its files with this one (and with every cache that does).
  std::shared_ptr<FileCache> make_sharing() const;

  /// Files read or parsed through this cache (a hit reads nothing, even one another cache read).
  int files_read() const;
  /// Texts, parsed meshes and mesh parts this cache holds.
  std::size_t entries_held() const;
  /// Lets go of every file that no load through this cache used since the last call (or since
  /// the cache was made): called after each load of a document, the cache holds what its
  /// latest load read, not every file the document ever named.
  void forget_unused();

  struct Impl;  ///< the loader's side (libbodyfmt/src/mesh_import/file_cache_impl.h)
  Impl& impl() const { return *impl_; }

 private:
  explicit FileCache(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace bodyfmt
#pragma GCC visibility pop
