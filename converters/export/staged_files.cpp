#include <bodyfmt/converters/names.h>
#include <bodyfmt/converters/staged_files.h>

#include <bodyfmt/read_file.h>

#include <fmt/format.h>

#include <filesystem>

namespace bodyfmt::converters {

std::string generated_folder(const std::string& option, const std::string& base, const OutputSet& output,
                             const std::string& model_name) {
  if (!option.empty()) return option;
  const std::string stem = output.to_stdout() ? model_name : output.main_path().stem().string();
  return base + "/" + file_stem(stem.empty() ? std::string("model") : stem);
}

std::string StagedFiles::unique_path(const std::string& base, const std::string& dot_extension) {
  std::string relative = folder_ + "/" + base + dot_extension;
  for (int n = 2; used_.count(relative); ++n) relative = fmt::format("{}/{}_{}{}", folder_, base, n, dot_extension);
  return relative;
}

std::optional<std::string> StagedFiles::add(const std::string& key, const std::string& relative, std::string contents) {
  output_.add(relative, std::move(contents));
  used_.insert(relative);
  by_key_.emplace(key, relative);
  return relative;
}

std::optional<std::string> StagedFiles::mesh(const std::string& key, const std::string& stem, const TriangleMesh& mesh,
                                             const std::optional<Material>& material, MeshFormat format,
                                             std::string& error) {
  if (auto it = by_key_.find(key); it != by_key_.end()) return it->second;
  const std::string base = file_stem(stem);
  const std::string relative = unique_path(base, "." + std::string(mesh_format_extension(format)));
  auto bytes = write_mesh(format, mesh, material, base, error);
  if (!bytes) {
    error = fmt::format("cannot encode mesh '{}': {}", relative, error);
    return std::nullopt;
  }
  return add(key, relative, std::move(*bytes));
}

std::optional<std::string> StagedFiles::copy(const std::string& source_path, std::uintmax_t max_bytes,
                                             std::string& error) {
  // One copy per file, however its path is spelled.
  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(source_path, ec);
  const std::string key = "copy:" + (ec ? source_path : canonical.string());
  if (auto it = by_key_.find(key); it != by_key_.end()) return it->second;
  std::string why;
  std::optional<std::string> bytes = read_regular_file(source_path, max_bytes, why);
  if (!bytes) {
    error = fmt::format("cannot read mesh '{}' to copy it: {}", source_path, why);
    return std::nullopt;
  }
  const std::filesystem::path p(source_path);
  return add(key, unique_path(file_stem(p.stem().string()), p.extension().string()), std::move(*bytes));
}

}  // namespace bodyfmt::converters
