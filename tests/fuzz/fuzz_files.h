#pragma once
// An input of the loader fuzz targets is a small folder in one byte string: the main body
// file, then any number of further files, each introduced by a line "#@file NAME" (NAME a
// relative path without ".."). The files are written to a scratch folder of the process,
// cleared before every input, so the loader reads includes and meshes (VRML, STL, OBJ, DAE)
// through its real readers.

#include <unistd.h>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace fuzz {

inline std::filesystem::path scratch_folder() {
  static const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("bodyfmt_fuzz_" + std::to_string(::getpid()));
  return folder;
}

/// Writes the files of `input` and returns the path of the main body file.
inline std::string write_folder(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path root = scratch_folder();
  std::error_code ec;
  std::filesystem::remove_all(root, ec);
  std::filesystem::create_directories(root, ec);
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::string name = "main.body";
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t marker = text.find("\n#@file ", begin);
    const std::size_t end = marker == std::string_view::npos ? text.size() : marker + 1;
    const std::filesystem::path path = root / name;
    std::filesystem::create_directories(path.parent_path(), ec);
    std::ofstream(path, std::ios::binary).write(text.data() + begin, static_cast<std::streamsize>(end - begin));
    if (marker == std::string_view::npos) break;
    const std::size_t name_begin = marker + 8;
    const std::size_t name_end = std::min(text.find('\n', name_begin), text.size());
    name = std::string(text.substr(name_begin, name_end - name_begin));
    if (name.empty() || name.find("..") != std::string::npos || name.front() == '/') name = "file";
    begin = name_end + 1;
  }
  return (root / "main.body").string();
}

}  // namespace fuzz
