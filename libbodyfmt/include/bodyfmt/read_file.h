#pragma once
/// The one way the library and the tools read a file: only a regular file (never a device, a
/// FIFO or a directory, which could block or never end), and only up to a size limit checked
/// before anything is read (issue 34: a plain stream on /dev/zero ended in std::bad_alloc).
#include <bodyfmt/export.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// A file's bytes in a buffer that nothing writes before the read does: a std::string of the
/// file's size would be zero-filled first, 24 MB for a 100,000-link model.
struct FileBytes {
  std::unique_ptr<char[]> data;
  std::size_t size = 0;
  std::string_view view() const { return {data.get(), size}; }
};

/// The bytes of the regular file at `path`, or nullopt with `why` set to a reason for the user
/// ("no such file", "is a directory, not a file", "is larger than the limit of N bytes", ...).
std::optional<FileBytes> read_regular_file_bytes(const std::string& path, std::uintmax_t max_bytes, std::string& why);

/// The same, as a string.
std::optional<std::string> read_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why);

/// Checks what read_regular_file checks, without reading (for files another library reads).
bool readable_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why);

/// The library's spelling from before the reader was public.
namespace detail {
using bodyfmt::FileBytes;
using bodyfmt::read_regular_file;
using bodyfmt::read_regular_file_bytes;
using bodyfmt::readable_regular_file;
}  // namespace detail

}  // namespace bodyfmt
#pragma GCC visibility pop
