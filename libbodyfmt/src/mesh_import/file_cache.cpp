#include "mesh_import/file_cache_impl.h"

#include <bodyfmt/read_file.h>

namespace bodyfmt {

FileCache::FileCache() : impl_(std::make_unique<Impl>(std::make_shared<Impl::Store>())) {}
FileCache::FileCache(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FileCache::~FileCache() = default;

std::shared_ptr<FileCache> FileCache::make_sharing() const {
  return std::shared_ptr<FileCache>(new FileCache(std::make_unique<Impl>(impl_->store)));
}

int FileCache::files_read() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->files_read;
}

std::size_t FileCache::entries_held() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->texts.held.size() + impl_->meshes.held.size() + impl_->assets.held.size();
}

void FileCache::forget_unused() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->texts.forget_unused();
  impl_->meshes.forget_unused();
  impl_->assets.forget_unused();
}

FileCache::Impl::Impl(std::shared_ptr<Store> shared_store) : store(std::move(shared_store)), mutex(store->mutex) {
  texts.shared = &store->texts;
  meshes.shared = &store->meshes;
  assets.shared = &store->assets;
}

FileCache::Impl::~Impl() {
  // What only this cache held goes now; the store forgets it at once rather than at another
  // cache's next forget_unused.
  std::lock_guard<std::mutex> lock(mutex);
  texts.held.clear();
  meshes.held.clear();
  assets.held.clear();
  texts.forget_unused();
  meshes.forget_unused();
  assets.forget_unused();
}

std::optional<FileCache::Impl::Stamp> FileCache::Impl::stamp_of(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || ec) return std::nullopt;
  Stamp stamp;
  stamp.time = std::filesystem::last_write_time(path, ec);
  if (ec) return std::nullopt;
  stamp.size = std::filesystem::file_size(path, ec);
  if (ec) return std::nullopt;
  return stamp;
}

std::optional<std::string> FileCache::Impl::read_text(const std::string& path, std::uintmax_t max_bytes,
                                                      std::string& why) {
  const std::optional<Stamp> stamp = stamp_of(path);
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (stamp) {
      const auto fresh = [&](const Text& t) { return t.stamp == *stamp && t.text.size() <= max_bytes; };
      if (std::shared_ptr<const Text> text = texts.find(path, fresh)) return text->text;
    }
    ++files_read;
  }
  // Read outside the lock: a slow file holds up no other cache.
  std::optional<std::string> text = read_regular_file(path, max_bytes, why);
  if (text && stamp) {
    std::lock_guard<std::mutex> lock(mutex);
    texts.put(path, std::make_shared<const Text>(Text{*stamp, *text}));
  }
  return text;
}

}  // namespace bodyfmt
