#include <bodyfmt/read_file.h>

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <string>

namespace bodyfmt {

namespace {

constexpr std::uintmax_t kLargestBuffer = std::numeric_limits<std::size_t>::max() / 2;

/// Why stat() or open() failed, in the words every tool prints (issue 45: a symbolic link
/// loop is not a missing file).
std::string error_text(int error) {
  switch (error) {
    case ENOENT: return "no such file";
    case ELOOP: return "too many levels of symbolic links (a symbolic link loop)";
    default: return std::strerror(error);
  }
}

/// The size of the regular file at `path` within `max_bytes`, or nullopt with `why` set.
std::optional<std::uintmax_t> regular_file_size(const std::string& path, std::uintmax_t max_bytes, std::string& why) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    why = error_text(errno);
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

std::optional<FileBytes> read_regular_file_bytes(const std::string& path, std::uintmax_t max_bytes, std::string& why) {
  const std::optional<std::uintmax_t> size = regular_file_size(path, max_bytes, why);
  if (!size) return std::nullopt;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    why = error_text(errno);
    return std::nullopt;
  }
  // Read at the size stat gave, into one buffer: a doubling buffer and its final copy would
  // hold a 250 MB model about three times over. A file that grew meanwhile is read to its end
  // (files such as /proc's report a size of 0), within the limit.
  FileBytes bytes;
  std::size_t capacity = static_cast<std::size_t>(*size) + 1;  // + 1: end of file needs no second buffer
  bytes.data.reset(new char[capacity]);
  for (;;) {
    if (bytes.size == capacity) {
      // One byte past the limit is enough to tell that the file crossed it.
      const std::uintmax_t ceiling = std::min<std::uintmax_t>(max_bytes, kLargestBuffer - 1) + 1;
      const std::size_t grown =
          static_cast<std::size_t>(std::min<std::uintmax_t>(std::max<std::uintmax_t>(capacity * 2U, 65536), ceiling));
      if (grown <= capacity) break;
      std::unique_ptr<char[]> larger(new char[grown]);
      std::memcpy(larger.get(), bytes.data.get(), bytes.size);
      bytes.data = std::move(larger);
      capacity = grown;
    }
    const ssize_t got = ::read(fd, bytes.data.get() + bytes.size, capacity - bytes.size);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      why = "a read error (" + std::string(std::strerror(errno)) + ")";
      ::close(fd);
      return std::nullopt;
    }
    if (got == 0) break;
    bytes.size += static_cast<std::size_t>(got);
  }
  ::close(fd);
  if (bytes.size > max_bytes) {
    why = fmt::format("grew past the limit of {} bytes while it was read", max_bytes);
    return std::nullopt;
  }
  return bytes;
}

std::optional<std::string> read_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why) {
  std::optional<FileBytes> bytes = read_regular_file_bytes(path, max_bytes, why);
  if (!bytes) return std::nullopt;
  return std::string(bytes->view());
}

}  // namespace bodyfmt
