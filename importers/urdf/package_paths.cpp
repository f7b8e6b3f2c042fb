#include "package_paths.h"

#include <bodyfmt/read_file.h>

#include <tinyxml2.h>

#include <cctype>
#include <cstdlib>
#include <system_error>

namespace bodyfmt::urdf_import {
namespace fs = std::filesystem;
namespace {

constexpr std::uintmax_t kMaxPackageXmlBytes = 1u << 20;

bool is_file(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

bool is_folder(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

std::string normal(const fs::path& path) {
  std::error_code ec;
  return fs::absolute(path, ec).lexically_normal().string();
}

// Tries `candidate`; records it. True when it is a file.
bool try_path(const fs::path& candidate, MeshLookup& result) {
  result.searched.push_back(normal(candidate));
  if (!is_file(candidate)) return false;
  result.path = result.searched.back();
  return true;
}

std::vector<std::string> split_paths(const char* list) {
  std::vector<std::string> out;
  if (!list) return out;
  std::string current;
  for (const char* p = list;; ++p) {
    if (*p == ':' || *p == '\0') {
      if (!current.empty()) out.push_back(current);
      current.clear();
      if (*p == '\0') break;
    } else {
      current += *p;
    }
  }
  return out;
}

bool found_in_package(const fs::path& package, const std::string& rest, MeshLookup& result) {
  if (!try_path(package / rest, result)) return false;
  result.package_folder = normal(package);
  return true;
}

bool find_in_package_root(const fs::path& root, const std::string& name, const std::string& rest, MeshLookup& result) {
  if (found_in_package(root / name, rest, result)) return true;
  return package_xml_name(root) == name && found_in_package(root, rest, result);
}

}  // namespace

std::string package_xml_name(const fs::path& folder) {
  const fs::path file = folder / "package.xml";
  std::string name;
  std::string why;
  // Bounded, and never a FIFO or a device: a package.xml is any file a downloaded tree holds.
  if (const std::optional<std::string> text = read_regular_file(file.string(), kMaxPackageXmlBytes, why)) {
    tinyxml2::XMLDocument doc;
    if (doc.Parse(text->data(), text->size()) == tinyxml2::XML_SUCCESS)
      if (const tinyxml2::XMLElement* package = doc.FirstChildElement("package"))
        if (const tinyxml2::XMLElement* n = package->FirstChildElement("name"))
          if (const char* value = n->GetText()) name = value;
    while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
    while (!name.empty() && std::isspace(static_cast<unsigned char>(name.front()))) name.erase(0, 1);
  }
  return name;
}

MeshLookup find_mesh(const std::string& uri, const MeshSearch& search) {
  MeshLookup result;
  const std::string package_scheme = "package://";
  const std::string file_scheme = "file://";
  if (uri.rfind(package_scheme, 0) == 0) {
    std::string rest = uri.substr(package_scheme.size());
    while (!rest.empty() && rest.front() == '/') rest.erase(0, 1);  // "package:///NAME/..." occurs in the wild
    const std::size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) {
      result.problem = "a package:// URI needs a package name and a path (package://NAME/PATH)";
      return result;
    }
    const std::string name = rest.substr(0, slash);
    const std::string path = rest.substr(slash + 1);
    for (const std::string& root : search.package_paths)
      if (find_in_package_root(root, name, path, result)) return result;
    if (search.use_ros_package_path)
      for (const std::string& root : split_paths(std::getenv("ROS_PACKAGE_PATH")))
        if (find_in_package_root(root, name, path, result)) return result;
    std::error_code ec;
    fs::path folder =
        fs::absolute(search.urdf_folder.empty() ? fs::path(".") : search.urdf_folder, ec).lexically_normal();
    while (true) {
      const std::string declared = package_xml_name(folder);
      if (declared == name || (declared.empty() && folder.filename() == name))
        if (found_in_package(folder, path, result)) return result;
      if (is_folder(folder / name) && found_in_package(folder / name, path, result)) return result;
      if (!folder.has_relative_path()) break;
      folder = folder.parent_path();
    }
    result.searched.push_back(
        "a package.xml naming '" + name + "' in " +
        fs::absolute(search.urdf_folder.empty() ? fs::path(".") : search.urdf_folder, ec).lexically_normal().string() +
        " or a folder above it, or a folder '" + name + "' in one of them");
    return result;
  }
  if (uri.rfind(file_scheme, 0) == 0) {
    const std::string path = uri.substr(file_scheme.size());
    if (!path.empty() && path.front() == '/') {
      try_path(path, result);
    } else {
      try_path(search.urdf_folder / path, result);
    }
    return result;
  }
  if (const std::size_t colon = uri.find("://"); colon != std::string::npos) {
    result.problem =
        "the URI scheme " + uri.substr(0, colon + 3) + " is not supported (package://, file:// and paths are)";
    return result;
  }
  const fs::path path(uri);
  try_path(path.is_absolute() ? path : search.urdf_folder / path, result);
  return result;
}

fs::path urdf_tree(const fs::path& urdf_folder) {
  std::error_code ec;
  const fs::path start = fs::weakly_canonical(fs::absolute(urdf_folder.empty() ? fs::path(".") : urdf_folder, ec), ec);
  for (fs::path folder = start;; folder = folder.parent_path()) {
    if (is_file(folder / "package.xml")) return folder;
    if (!folder.has_relative_path()) break;
  }
  return start;
}

bool inside_tree(const std::string& file, const fs::path& tree) {
  std::error_code ec;
  const fs::path real = fs::canonical(file, ec);
  if (ec) return false;
  const fs::path relative = real.lexically_relative(tree);
  return !relative.empty() && *relative.begin() != ".." && *relative.begin() != ".";
}

}  // namespace bodyfmt::urdf_import
