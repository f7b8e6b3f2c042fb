#include <bodyfmt/package_map.h>

#include <bodyfmt/read_file.h>

#include <tinyxml2.h>

#include <cstdlib>
#include <system_error>

namespace bodyfmt {
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

fs::path absolute_folder(const fs::path& folder) {
  std::error_code ec;
  return fs::absolute(folder.empty() ? fs::path(".") : folder, ec).lexically_normal();
}

std::string trimmed(std::string text) {
  const char* const space = " \t\r\n";
  text.erase(0, text.find_first_not_of(space));
  const std::size_t last = text.find_last_not_of(space);
  text.erase(last == std::string::npos ? 0 : last + 1);
  return text;
}

/// The package.xml of `folder`: false when there is none; else true, with `name` the name it
/// declares (empty when it declares none or cannot be read, `why` saying which).
bool read_package_xml(const fs::path& folder, std::string& name, std::string& why) {
  const fs::path file = folder / "package.xml";
  if (!is_file(file)) return false;
  name.clear();
  // Bounded, and never a FIFO or a device: a package.xml is any file a downloaded tree holds.
  const std::optional<std::string> text = read_regular_file(file.string(), kMaxPackageXmlBytes, why);
  if (!text) {
    why = file.string() + " cannot be read: " + why;
    return true;
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text->data(), text->size()) != tinyxml2::XML_SUCCESS) {
    why = file.string() + " cannot be read as XML: " + std::string(doc.ErrorStr());
    return true;
  }
  const tinyxml2::XMLElement* package = doc.FirstChildElement("package");
  const tinyxml2::XMLElement* element = package ? package->FirstChildElement("name") : nullptr;
  const char* value = element ? element->GetText() : nullptr;
  name = trimmed(value ? value : "");
  if (name.empty()) why = file.string() + " declares no <package><name>";
  return true;
}

// Tries `candidate`; records it. True when it is a file.
bool try_path(const fs::path& candidate, PackageLookup& result) {
  result.searched.push_back(normal(candidate));
  if (!is_file(candidate)) return false;
  result.path = result.searched.back();
  return true;
}

bool found_in_package(const fs::path& package, const std::string& rest, PackageLookup& result) {
  if (!try_path(package / rest, result)) return false;
  result.package_folder = normal(package);
  return true;
}

bool find_in_package_root(const fs::path& root, const std::string& name, const std::string& rest,
                          PackageLookup& result) {
  if (found_in_package(root / name, rest, result)) return true;
  return package_xml_name(root) == name && found_in_package(root, rest, result);
}

std::vector<std::string> ros_package_path() {
  std::vector<std::string> out;
  const char* list = std::getenv("ROS_PACKAGE_PATH");
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

}  // namespace

bool is_package_uri(std::string_view uri) { return uri.substr(0, 10) == "package://"; }

std::string package_xml_name(const fs::path& folder) {
  std::string name, why;
  read_package_xml(folder, name, why);
  return name;
}

PackageLookup find_package_file(const std::string& uri, const PackageSearch& search) {
  PackageLookup result;
  if (!is_package_uri(uri)) {
    result.problem = "\"" + uri + "\" is not a package:// URI";
    return result;
  }
  std::string rest = uri.substr(10);
  while (!rest.empty() && rest.front() == '/') rest.erase(0, 1);
  const std::size_t slash = rest.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == rest.size()) {
    result.problem = "a package:// URI needs a package name and a path (package://NAME/PATH)";
    return result;
  }
  const std::string name = rest.substr(0, slash);
  const std::string path = rest.substr(slash + 1);
  for (const std::string& root : search.package_paths)
    if (find_in_package_root(root, name, path, result)) return result;
  if (search.use_ros_package_path)
    for (const std::string& root : ros_package_path())
      if (find_in_package_root(root, name, path, result)) return result;
  const fs::path start = absolute_folder(search.referring_folder);
  for (fs::path folder = start;; folder = folder.parent_path()) {
    const std::string declared = package_xml_name(folder);
    if (declared == name || (declared.empty() && folder.filename() == name))
      if (found_in_package(folder, path, result)) return result;
    if (is_folder(folder / name) && found_in_package(folder / name, path, result)) return result;
    if (!folder.has_relative_path()) break;
  }
  result.searched.push_back("a package.xml naming '" + name + "' in " + start.string() +
                            " or a folder above it, or a folder '" + name + "' in one of them");
  return result;
}

std::optional<RosPackage> find_ros_package(const fs::path& folder, std::string& why) {
  const fs::path start = absolute_folder(folder);
  for (fs::path dir = start;; dir = dir.parent_path()) {
    std::string name;
    if (read_package_xml(dir, name, why)) {
      if (name.empty()) return std::nullopt;
      return RosPackage{dir, name};
    }
    if (!dir.has_relative_path()) break;
  }
  why = "no package.xml in " + start.string() + " or any folder above it";
  return std::nullopt;
}

std::optional<std::string> path_in_package(const fs::path& root, const fs::path& path) {
  const fs::path inside = path.lexically_normal().lexically_relative(root.lexically_normal());
  if (inside.empty() || *inside.begin() == "..") return std::nullopt;
  return inside.generic_string();
}

bool is_package_name(std::string_view name) {
  if (name.empty() || name == "." || name == "..") return false;
  for (const char c : name)
    if (c == '/' || c == '\\' || static_cast<unsigned char>(c) <= ' ' || c == 0x7f) return false;
  return true;
}

fs::path package_tree(const fs::path& folder) {
  std::error_code ec;
  const fs::path start = fs::weakly_canonical(absolute_folder(folder), ec);
  for (fs::path dir = start;; dir = dir.parent_path()) {
    if (is_file(dir / "package.xml")) return dir;
    if (!dir.has_relative_path()) break;
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

}  // namespace bodyfmt
