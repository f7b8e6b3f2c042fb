#include "ros_package.h"

#include <tinyxml2.h>

namespace bodyfmt::urdf {

namespace fs = std::filesystem;

std::optional<RosPackage> find_ros_package(const fs::path& start, std::string& why) {
  std::error_code ec;
  fs::path dir = fs::absolute(start, ec).lexically_normal();
  for (;;) {
    const fs::path manifest = dir / "package.xml";
    if (fs::is_regular_file(manifest, ec)) {
      tinyxml2::XMLDocument doc;
      if (doc.LoadFile(manifest.c_str()) != tinyxml2::XML_SUCCESS) {
        why = manifest.string() + " cannot be read as XML: " + std::string(doc.ErrorStr());
        return std::nullopt;
      }
      const tinyxml2::XMLElement* root = doc.FirstChildElement("package");
      const tinyxml2::XMLElement* name = root ? root->FirstChildElement("name") : nullptr;
      const char* text = name ? name->GetText() : nullptr;
      if (!text || !*text) {
        why = manifest.string() + " declares no <package><name>";
        return std::nullopt;
      }
      std::string trimmed(text);
      trimmed.erase(0, trimmed.find_first_not_of(" \t\r\n"));
      trimmed.erase(trimmed.find_last_not_of(" \t\r\n") + 1);
      return RosPackage{dir, trimmed};
    }
    // Trailing separators make parent_path() return the same folder: strip before comparing.
    const fs::path parent = dir.has_relative_path() ? dir.parent_path() : dir;
    if (parent == dir) break;
    dir = parent;
  }
  why = "no package.xml in " + fs::absolute(start, ec).lexically_normal().string() + " or any folder above it";
  return std::nullopt;
}

std::optional<std::string> path_in_package(const fs::path& root, const fs::path& path) {
  const fs::path inside = path.lexically_normal().lexically_relative(root.lexically_normal());
  if (inside.empty() || *inside.begin() == "..") return std::nullopt;
  return inside.generic_string();
}

}  // namespace bodyfmt::urdf
