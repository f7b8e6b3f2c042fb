#include "io/read_file.h"

#include <fmt/format.h>

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>

namespace bodyfmt::detail {

namespace {

/// The size of the regular file at `path` within `max_bytes`, or nullopt with `why` set.
std::optional<std::uintmax_t> regular_file_size(const std::string& path, std::uintmax_t max_bytes, std::string& why) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    why = errno == ENOENT ? std::string("no such file") : std::string(std::strerror(errno));
    return std::nullopt;
  }
  if (S_ISDIR(st.st_mode)) {
    why = "is a directory, not a file";
    return std::nullopt;
  }
  if (!S_ISREG(st.st_mode)) {
    why = "is not a regular file (a device, a FIFO or a socket)";
    return std::nullopt;
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes) {
    why = fmt::format("is {} bytes, larger than the limit of {} bytes (LoadOptions::max_file_bytes, --max-file-size)",
                      size, max_bytes);
    return std::nullopt;
  }
  return size;
}

}  // namespace

bool readable_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why) {
  return regular_file_size(path, max_bytes, why).has_value();
}

std::optional<std::string> read_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why) {
  const std::optional<std::uintmax_t> size = regular_file_size(path, max_bytes, why);
  if (!size) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    why = std::strerror(errno);
    return std::nullopt;
  }
  // Read at the size stat gave, into one buffer: a doubling buffer and its final copy would
  // hold a 250 MB model about three times over. A file that grew meanwhile is read to its end
  // (files such as /proc's report a size of 0), within the limit.
  std::string text(static_cast<std::size_t>(*size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (!in.eof() && !in.bad()) {
    in.clear();
    char buffer[65536];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
      if (text.size() + static_cast<std::size_t>(in.gcount()) > max_bytes) {
        why = fmt::format("grew past the limit of {} bytes while it was read", max_bytes);
        return std::nullopt;
      }
      text.append(buffer, static_cast<std::size_t>(in.gcount()));
    }
  }
  if (in.bad()) {
    why = "a read error";
    return std::nullopt;
  }
  return text;
}

}  // namespace bodyfmt::detail
