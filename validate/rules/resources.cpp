// Resource rules beyond the loader's (which reports unresolvable URIs and missing or
// unreadable files): portability of the paths themselves.

#include "rule_context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <system_error>
#include <vector>

namespace bodyfmt::validate::detail {
namespace {

namespace fs = std::filesystem;

bool is_absolute_uri(const std::string& uri) {
  std::string path = uri;
  if (path.rfind("file://", 0) == 0) path = path.substr(7);
  if (!path.empty() && (path[0] == '/' || path[0] == '\\')) return true;
  // A Windows drive letter: C:\ or C:/
  return path.size() >= 3 && std::isalpha(static_cast<unsigned char>(path[0])) && path[1] == ':' &&
         (path[2] == '/' || path[2] == '\\');
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Directory listings, read once per check.
class DirectoryCache {
 public:
  const std::vector<std::string>& list(const fs::path& dir) {
    auto it = cache_.find(dir.string());
    if (it != cache_.end()) return it->second;
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator d(dir, ec), end; !ec && d != end; d.increment(ec))
      names.push_back(d->path().filename().string());
    return cache_.emplace(dir.string(), std::move(names)).first->second;
  }

 private:
  std::map<std::string, std::vector<std::string>> cache_;
};

// Walks the path component by component against the directory listings. Returns the path
// as spelt on disk when some component exists only with a different letter case (which a
// case-insensitive file system would accept and a case-sensitive one would not).
std::optional<std::string> case_mismatch(const std::string& resolved, DirectoryCache& dirs) {
  const fs::path path(resolved);
  fs::path on_disk = path.has_root_path() ? path.root_path() : fs::path(".");
  fs::path shown = path.root_path();
  bool mismatch = false;
  for (const fs::path& part : path.relative_path()) {
    const std::string name = part.string();
    if (name == "." || name == ".." || name.empty()) {
      on_disk /= part;
      shown /= part;
      continue;
    }
    const std::vector<std::string>& names = dirs.list(on_disk);
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      on_disk /= name;
      shown /= name;
      continue;
    }
    auto it = std::find_if(names.begin(), names.end(), [&](const std::string& n) { return lower(n) == lower(name); });
    if (it == names.end()) return std::nullopt;  // missing: the loader reports it
    mismatch = true;
    on_disk /= *it;
    shown /= *it;
  }
  if (!mismatch) return std::nullopt;
  return shown.string();
}

void check_uri(const RuleContext& ctx, const std::string& uri, const std::string& resolved, const SourceLocation& at,
               DirectoryCache& dirs) {
  if (is_absolute_uri(uri)) {
    ctx.report("resource-absolute-path", at,
               fmt::format("\"{}\" is an absolute path: the model works only on this machine", uri),
               "use a path relative to the .body file, or package:// / ${SHARE}");
  }
  if (resolved.empty()) return;
  if (auto actual = case_mismatch(resolved, dirs)) {
    ctx.report("resource-case-mismatch", at,
               fmt::format("\"{}\" exists on disk only with different letter case: \"{}\"", uri, *actual),
               "spell the path exactly as on disk; case-sensitive file systems (Linux) will not find it");
  }
}

}  // namespace

void check_resources(const RuleContext& ctx) {
  DirectoryCache dirs;
  for (const Link& link : ctx.model.links) {
    for (const Shape& shape : link.shapes) {
      const SourceLocation at = first_known({shape.source, link.source});
      if (const auto* mesh = geometry_if<MeshResource>(shape.geometry))
        check_uri(ctx, mesh->uri, mesh->resolved_path, at, dirs);
      if (shape.appearance.texture)
        check_uri(ctx, shape.appearance.texture->uri, shape.appearance.texture->resolved_path, at, dirs);
    }
  }
}

}  // namespace bodyfmt::validate::detail
