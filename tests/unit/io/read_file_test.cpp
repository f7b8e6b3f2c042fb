// io/read_file.cpp (bodyfmt/read_file.h): the file's bytes exactly, the size limit, and the files it refuses.

#include <bodyfmt/read_file.h>

#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

namespace {

std::string write_temp(const std::string& name, const std::string& bytes) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace

TEST_CASE("read_regular_file_bytes returns every byte, NULs and all, for sizes around its buffer") {
  std::mt19937 random(7);
  for (std::size_t size : {0UL, 1UL, 4095UL, 65536UL, 65537UL, 1000003UL}) {
    CAPTURE(size);
    std::string bytes(size, '\0');
    for (char& c : bytes) c = static_cast<char>(random());
    const std::string path = write_temp("bodyfmt_read_file_test.bin", bytes);
    std::string why;
    const auto read = bodyfmt::detail::read_regular_file_bytes(path, 1 << 20, why);
    REQUIRE(read);
    CHECK(read->view() == bytes);
    CHECK(why.empty());
    const auto text = bodyfmt::detail::read_regular_file(path, 1 << 20, why);
    REQUIRE(text);
    CHECK(*text == bytes);
    std::remove(path.c_str());
  }
}

TEST_CASE("read_regular_file_bytes refuses a file over the limit, a folder and a missing file") {
  const std::string path = write_temp("bodyfmt_read_file_limit.txt", std::string(101, 'x'));
  std::string why;
  CHECK(bodyfmt::detail::read_regular_file_bytes(path, 101, why));
  CHECK_FALSE(bodyfmt::detail::read_regular_file_bytes(path, 100, why));
  CHECK(why.find("larger than the limit of 100 bytes") != std::string::npos);
  std::remove(path.c_str());
  CHECK_FALSE(bodyfmt::detail::read_regular_file_bytes(std::filesystem::temp_directory_path().string(), 100, why));
  CHECK(why == "is a directory, not a file");
  CHECK_FALSE(bodyfmt::detail::read_regular_file_bytes(path, 100, why));
  CHECK(why == "no such file");
}

TEST_CASE("read_regular_file_bytes names a symbolic link loop as one, not as a missing file (issue 45)") {
  const std::filesystem::path loop = std::filesystem::temp_directory_path() / "bodyfmt_read_file_loop.body";
  std::error_code ec;
  std::filesystem::remove(loop, ec);
  std::filesystem::create_symlink(loop.filename(), loop);
  std::string why;
  CHECK_FALSE(bodyfmt::detail::read_regular_file_bytes(loop.string(), 100, why));
  CHECK(why == "too many levels of symbolic links (a symbolic link loop)");
  CHECK_FALSE(bodyfmt::readable_regular_file(loop.string(), 100, why));
  CHECK(why == "too many levels of symbolic links (a symbolic link loop)");
  std::filesystem::remove(loop, ec);
}

TEST_CASE("read_regular_file_bytes reads a file whose size stat reports as 0, within the limit") {
  // /proc files report a size of 0 and are read to their end, growing the buffer.
  std::string why;
  const auto status = bodyfmt::detail::read_regular_file_bytes("/proc/self/status", 1 << 20, why);
  REQUIRE(status);
  CHECK(status->view().find("Name:") == 0);
  // The same file past a limit smaller than its text: refused as having grown past it.
  CHECK_FALSE(bodyfmt::detail::read_regular_file_bytes("/proc/self/status", 64, why));
  CHECK(why == "grew past the limit of 64 bytes while it was read");
}
