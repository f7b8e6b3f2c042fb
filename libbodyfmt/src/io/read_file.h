#pragma once
// The one way the library reads a file: only a regular file (never a device, a FIFO or a
// directory, which could block or never end), and only up to a size limit checked before
// anything is read.

#include <cstdint>
#include <optional>
#include <string>

namespace bodyfmt::detail {

/// Text of the regular file at `path`, or nullopt with `why` set to a reason for the user
/// ("no such file", "is a directory, not a file", "is larger than the limit of N bytes", ...).
std::optional<std::string> read_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why);

/// Checks what read_regular_file checks, without reading (for files another library reads).
bool readable_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why);

}  // namespace bodyfmt::detail
