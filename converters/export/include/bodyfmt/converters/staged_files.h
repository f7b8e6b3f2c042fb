#pragma once
/// The files an export writes beside its main file (meshes, copied resources), each under a
/// unique relative path in one folder, each written once however often it is used.
#include <bodyfmt/converters/mesh_writer.h>
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/load.h>

#include <map>
#include <optional>
#include <set>
#include <string>

namespace bodyfmt::converters {

/// The folder for an export's generated files: `option` when the user gave one, else
/// `base/STEM` with the output's file stem (the model's name for standard output), so that
/// exports into one folder never share generated file names.
std::string generated_folder(const std::string& option, const std::string& base, const OutputSet& output,
                             const std::string& model_name);

class StagedFiles {
 public:
  /// Files go to `folder` (relative to the output's directory) in `output`.
  StagedFiles(OutputSet& output, std::string folder) : output_(output), folder_(std::move(folder)) {}

  /// Stages `mesh` once per `key`, encoded as `format`, named after `stem` (made a safe file
  /// name, with _2, _3, ... when taken). Returns the relative path, or nullopt with `error`
  /// set when the mesh cannot be encoded.
  std::optional<std::string> mesh(const std::string& key, const std::string& stem, const TriangleMesh& mesh,
                                  const std::optional<Material>& material, MeshFormat format, std::string& error);

  /// Stages a copy of the file at `source_path` once, under its own (safe) name. Returns the
  /// relative path, or nullopt with `error` set when it cannot be read.
  /// The file is read through the bounded reader (bodyfmt/read_file.h): a regular file of at
  /// most `max_bytes`.
  std::optional<std::string> copy(const std::string& source_path, std::uintmax_t max_bytes, std::string& error);
  std::optional<std::string> copy(const std::string& source_path, std::string& error) {
    return copy(source_path, LoadOptions{}.max_file_bytes, error);
  }

 private:
  std::string unique_path(const std::string& base, const std::string& dot_extension);
  std::optional<std::string> add(const std::string& key, const std::string& relative, std::string contents);

  OutputSet& output_;
  std::string folder_;
  std::map<std::string, std::string> by_key_;  // key -> relative path
  std::set<std::string> used_;
};

}  // namespace bodyfmt::converters
