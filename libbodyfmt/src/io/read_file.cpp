#include "io/read_file.h"

#include <fmt/format.h>

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace bodyfmt::detail {

bool readable_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    why = errno == ENOENT ? std::string("no such file") : std::string(std::strerror(errno));
    return false;
  }
  if (S_ISDIR(st.st_mode)) {
    why = "is a directory, not a file";
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    why = "is not a regular file (a device, a FIFO or a socket)";
    return false;
  }
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    why = fmt::format("is {} bytes, larger than the limit of {} bytes (LoadOptions::max_file_bytes, --max-file-size)",
                      static_cast<std::uintmax_t>(st.st_size), max_bytes);
    return false;
  }
  return true;
}

std::optional<std::string> read_regular_file(const std::string& path, std::uintmax_t max_bytes, std::string& why) {
  if (!readable_regular_file(path, max_bytes, why)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    why = std::strerror(errno);
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    why = "a read error";
    return std::nullopt;
  }
  return std::move(text).str();
}

}  // namespace bodyfmt::detail
