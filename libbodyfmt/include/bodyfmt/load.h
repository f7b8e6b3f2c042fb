#pragma once
/// Loading a Choreonoid Body file into a Model.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

struct LoadOptions;
class FileCache;

/// Reads a model file of another format that a wrapper body file names in `model_file`
/// (body-format-spec §2.4): `text` is the file's content, read under the options' limits;
/// `path` names it in locations. Reports to `sink` with locations in that file; returns nullopt
/// when no model comes out.
using ModelFileReader = std::function<std::optional<Model>(const std::string& path, const std::string& text,
                                                           const LoadOptions& options, DiagnosticSink& sink)>;

struct LoadOptions {
  /// "Billion laughs" guard: the document's node count with every alias expanded. A
  /// 1,000,000-link model written one link per line has about 31 million nodes.
  std::size_t max_expanded_yaml_nodes = 40'000'000;
  /// Nesting limit for YAML sequences and mappings, counted through aliases.
  int max_yaml_depth = 200;
  /// Largest file the loader reads (the body file, SubBody and YAML resources, mesh files).
  /// Only regular files are read: never a device, a FIFO or a directory.
  std::uintmax_t max_file_bytes = 256u << 20;
  /// Most triangles of a binary STL mesh: its import takes about 1.5 KB per triangle (assimp's
  /// scene and ours), so a 250 MiB file would need 7 GB.
  std::uint32_t max_mesh_triangles = 1'000'000;
  /// Import external mesh files (Resource nodes) into Model::meshes.
  bool load_meshes = true;
  /// Extra roots for `package://NAME/...` URIs, searched before ROS_PACKAGE_PATH
  /// (bodyfmt/package_map.h: the search every reader shares).
  std::vector<std::string> package_paths;
  /// Search the folders of $ROS_PACKAGE_PATH for package:// URIs (--no-ros-package-path).
  bool use_ros_package_path = true;
  /// Texts that stand in for SubBody and YAML resource files on disk, by canonical path
  /// (std::filesystem::weakly_canonical): `bodycheck --fix` re-loads its edits from memory
  /// before it writes them.
  std::map<std::string, std::string> file_texts;
  /// Read the items of `links` while the file is parsed, so that the YAML tree never holds
  /// them all (a 100,000-link model). The model and the findings are the same either way;
  /// false keeps the whole tree first, as a reference for tests.
  bool stream_links = true;
  /// Readers of the formats a wrapper body file's `model_file` may name besides .body, .yaml
  /// and .yml (which this loader reads), by extension with its dot, as Choreonoid matches it
  /// (case-sensitive): {".urdf", ...}. libbodyfmt reads no other format itself; a wrapper naming
  /// an extension without a reader gets a located `load-wrapper` error. The bodyfmt tools
  /// install the URDF importer here.
  std::map<std::string, ModelFileReader> model_file_readers;
  /// Included files and parsed meshes kept across loads while their modification time and
  /// size stay the same (bodyfmt/file_cache.h); null: every load reads them.
  std::shared_ptr<FileCache> file_cache;
  /// Called with the path of each file the loader read as model text: the body file, then
  /// each sub-body and wrapper model file whose top level is a body's (or a wrapper's)
  /// mapping, each YAML resource whose top level is elements, each scene file whose top level
  /// is a mapping; a ModelFileReader calls it for a file it read as its format. A report
  /// quotes source lines of these files only (SourceLines::add_file): a file that a hostile
  /// model names (a SubBody `uri`, a wrapper's `model_file`) but that is no model is never
  /// printed, not even its first line. May be called from the loading thread; null: nobody asks.
  std::function<void(const std::string& path)> on_model_text;
};

/// Loads a .body file. Reports every problem it can find to `sink` and returns the model
/// even when some of them are errors, so that one run lists them all. Returns nullopt only
/// when nothing usable exists: the file cannot be read, its YAML is malformed or exceeds the
/// limits, or it has no links.
std::optional<Model> load_body(const std::string& path, const LoadOptions& options, DiagnosticSink& sink);

/// Same, from text; `file_name` is used in locations and to resolve relative URIs.
std::optional<Model> load_body_string(const std::string& text, const std::string& file_name, const LoadOptions& options,
                                      DiagnosticSink& sink);

}  // namespace bodyfmt
#pragma GCC visibility pop
