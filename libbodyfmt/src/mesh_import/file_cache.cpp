#include "mesh_import/file_cache_impl.h"

#include <bodyfmt/read_file.h>

namespace bodyfmt {

FileCache::FileCache() : impl_(std::make_unique<Impl>()) {}
FileCache::~FileCache() = default;

int FileCache::files_read() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->files_read;
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
  std::lock_guard<std::mutex> lock(mutex);
  if (stamp) {
    auto it = texts.find(path);
    if (it != texts.end() && it->second.stamp == *stamp && it->second.text.size() <= max_bytes) return it->second.text;
  }
  ++files_read;
  std::optional<std::string> text = read_regular_file(path, max_bytes, why);
  if (text && stamp) texts[path] = Text{*stamp, *text};
  return text;
}

}  // namespace bodyfmt
