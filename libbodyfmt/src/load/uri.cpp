#include "load/uri.h"

#include <bodyfmt/body_keys.h>

#include "load/mapping_reader.h"

#include <bodyfmt/package_map.h>

#include <cstdlib>
#include <filesystem>

namespace bodyfmt::detail {

std::string resolve_uri(LoadContext& ctx, const yaml::NodeRef& at, const std::string& uri,
                        const std::string& referring_file) {
  namespace fs = std::filesystem;
  std::string path = uri;
  const std::string file_scheme = "file://";
  if (path.rfind(file_scheme, 0) == 0) path = path.substr(file_scheme.size());
  auto scheme_end = path.find("://");
  if (scheme_end != std::string::npos) {
    std::string scheme = path.substr(0, scheme_end);
    if (scheme != "package") {
      ctx.report("load-uri", at, "the \"" + scheme + "\" scheme in URI \"" + uri + "\" is not supported");
      return {};
    }
    // The package map every reader shares (a URDF beside this file resolves it the same way).
    PackageSearch search{ctx.package_paths, ctx.use_ros_package_path, fs::path(referring_file).parent_path()};
    PackageLookup found = find_package_file(path, search);
    if (!found.path.empty()) return found.path;
    if (!found.problem.empty()) {
      ctx.report("load-uri", at, "URI \"" + uri + "\": " + found.problem);
      return {};
    }
    std::string rest = path.substr(scheme_end + 3);
    while (!rest.empty() && rest.front() == '/') rest.erase(0, 1);
    const std::string package = rest.substr(0, rest.find('/'));
    ctx.report("load-uri", at, "package \"" + package + "\" of URI \"" + uri + "\" is not found",
               "add its parent folder to ROS_PACKAGE_PATH or pass it with --package-path");
    return {};
  }
  if (path.rfind("${", 0) == 0) {
    auto close = path.find('}');
    std::string variable = path.substr(2, close == std::string::npos ? std::string::npos : close - 2);
    const char* value = variable == "HOME" ? std::getenv("HOME") : nullptr;
    if (!value) {
      ctx.report("load-uri", at, "path variable \"" + variable + "\" in \"" + uri + "\" is not defined");
      return {};
    }
    path = std::string(value) + path.substr(close + 1);
  }
  fs::path p(path);
  if (p.is_relative()) p = fs::path(referring_file).parent_path() / p;
  return p.lexically_normal().string();
}

void read_mesh_metadata(LoadContext& ctx, const yaml::NodeRef& metadata, MeshResource& mesh) {
  auto apply_unit = [&](const std::string& unit, const yaml::NodeRef& at) {
    if (unit == "millimeter")
      mesh.length_scale = 0.001;
    else if (unit == "inch")
      mesh.length_scale = 0.0254;
    else if (unit == "meter")
      mesh.length_scale = 1.0;
    else
      ctx.report("load-ignored-value", at, "unknown length unit \"" + unit + "\"");
  };
  if (metadata->is_scalar()) {
    // Legacy form: space-separated words (body-format-spec §9.4).
    std::string words(metadata->scalar());
    std::size_t start = 0;
    while (start < words.size()) {
      std::size_t end = words.find(' ', start);
      std::string word = words.substr(start, end - start);
      if (word == "y_upper")
        mesh.y_up = true;
      else if (!word.empty())
        apply_unit(word, metadata);
      if (end == std::string::npos) break;
      start = end + 1;
    }
    return;
  }
  MappingReader r(ctx, metadata, "metadata");
  if (auto unit = r.take({"length_unit"})) apply_unit(std::string(unit->scalar()), unit);
  if (auto axis = r.take({"upper_axis"})) {
    if (axis->scalar() == "Y")
      mesh.y_up = true;
    else if (axis->scalar() != "Z")
      ctx.report("load-ignored-value", axis, "upper_axis must be Y or Z");
  }
  r.report_unknown(body_key_names("metadata"));
}

std::string file_identity(const std::string& path) {
  std::error_code ec;
  std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
  if (!ec) return canonical.string();
  std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  return (ec ? std::filesystem::path(path) : absolute).lexically_normal().string();
}

std::string include_chain_text(const std::vector<std::string>& chain, const std::string& last) {
  std::string text;
  for (const std::string& file : chain) text += std::filesystem::path(file).filename().string() + " -> ";
  return text + std::filesystem::path(last).filename().string();
}

}  // namespace bodyfmt::detail
