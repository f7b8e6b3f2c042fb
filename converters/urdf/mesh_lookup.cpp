#include "mesh_lookup.h"

#include <filesystem>
#include <system_error>

namespace bodyfmt::urdf_import {
namespace fs = std::filesystem;

PackageLookup find_mesh(const std::string& uri, const PackageSearch& search) {
  if (is_package_uri(uri)) return find_package_file(uri, search);
  PackageLookup result;
  const std::string file_scheme = "file://";
  std::string path = uri;
  if (uri.rfind(file_scheme, 0) == 0) {
    path = uri.substr(file_scheme.size());
  } else if (const std::size_t colon = uri.find("://"); colon != std::string::npos) {
    result.problem =
        "the URI scheme " + uri.substr(0, colon + 3) + " is not supported (package://, file:// and paths are)";
    return result;
  }
  const fs::path file(path);
  std::error_code ec;
  const std::string candidate =
      fs::absolute(file.is_absolute() ? file : search.referring_folder / file, ec).lexically_normal().string();
  result.searched.push_back(candidate);
  if (fs::is_regular_file(candidate, ec)) result.path = candidate;
  return result;
}

}  // namespace bodyfmt::urdf_import
