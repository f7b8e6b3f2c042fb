#pragma once
/// Files read by earlier loads, kept while their modification time and size stay the same
/// (LoadOptions::file_cache): a language server loads a model at every keystroke, and must
/// re-read only its buffer, not parse its meshes or read its included files each time. The
/// findings of a load are the same with or without it: a mesh file's findings are replayed at
/// the `uri:` that names it in the new load. Safe to share between threads.
#include <bodyfmt/export.h>

#include <memory>

#pragma GCC visibility push(default)
namespace bodyfmt {

class FileCache {
 public:
  FileCache();
  ~FileCache();
  FileCache(const FileCache&) = delete;
  FileCache& operator=(const FileCache&) = delete;

  /// Files read or parsed through the cache (a hit reads nothing).
  int files_read() const;

  struct Impl;  ///< the loader's side (libbodyfmt/src/mesh_import/file_cache_impl.h)
  Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace bodyfmt
#pragma GCC visibility pop
