#include "package_paths.h"

#include <tinyxml2.h>

#include <cctype>
#include <cstdlib>
#include <system_error>

namespace bodyfmt::urdf_import {
namespace fs = std::filesystem;
namespace {

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

bool find_in_package_root(const fs::path& root, const std::string& name, const std::string& rest, MeshLookup& result) {
  if (try_path(root / name / rest, result)) return true;
  return package_xml_name(root) == name && try_path(root / rest, result);
}

}  // namespace

std::string package_xml_name(const fs::path& folder) {
  const fs::path file = folder / "package.xml";
  std::string name;
  if (is_file(file)) {
    tinyxml2::XMLDocument doc;
    if (doc.LoadFile(file.string().c_str()) == tinyxml2::XML_SUCCESS)
      if (const tinyxml2::XMLElement* package = doc.FirstChildElement("package"))
        if (const tinyxml2::XMLElement* n = package->FirstChildElement("name"))
          if (const char* text = n->GetText()) name = text;
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
        if (try_path(folder / path, result)) return result;
      if (is_folder(folder / name) && try_path(folder / name / path, result)) return result;
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

}  // namespace bodyfmt::urdf_import
