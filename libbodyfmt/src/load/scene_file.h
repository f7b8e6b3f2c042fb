#pragma once
// Choreonoid scene files (.scen) named by a Resource node (body-format-spec §9.2): read with
// the element grammar of the body loader, in their own angle unit, as Choreonoid's
// StdSceneLoader reads them with a fresh StdSceneReader.

#include <bodyfmt/load.h>
#include <bodyfmt/model.h>

#include "load/elements.h"
#include "load/load_context.h"

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::detail {

class SceneFiles {
 public:
  /// How many scene files may include one another, one inside the next.
  static constexpr std::size_t kMaxNesting = 16;

  /// `include_depth`: the depths of the included files being read, added up, which the
  /// caller shares with its own includes (YAML resources).
  SceneFiles(const LoadOptions& options, LoadContext& ctx, int& include_depth)
      : options_(options), ctx_(ctx), chain_depth_(include_depth) {}

  /// Adds the shapes of the scene file at `path`, which `uri` names, to `reader`'s link under
  /// `frame` (the Resource node's); `resource` carries the node's metadata (length unit,
  /// upper axis). Every problem is reported, located in the scene file where it is written.
  /// With `node` (the Resource's node/fragment value), only the first node of that name, in
  /// depth-first order, is read, as StdSceneReader's extractNamedSceneNodes takes it: detached
  /// and re-centred (the rotation and scale above it and its own are kept, every translation
  /// above it and its own dropped), under the Resource node's frame.
  void read(ElementReader& reader, const SourceLocation& uri, const std::string& path, const MeshResource& resource,
            const ElementFrame& frame, const yaml::NodeRef& node = {});
  /// A Shape whose geometry is a Resource naming a scene file: Choreonoid takes the mesh of
  /// the file's one shape, which must have no transform of its own (StdSceneReader's
  /// readResourceAsGeometry), and the Shape's appearance. Adds that shape, else reports why.
  void read_as_geometry(ElementReader& reader, Shape shape, const ElementFrame& frame);

 private:
  struct File {
    std::unique_ptr<yaml::Document> document;
    yaml::NodeRef scene;  ///< the `scene` value; empty when the file cannot be used (reported)
    bool degrees = true;  ///< the scene file's own angle_unit
    int depth = 0;        ///< the document's nesting depth
  };

  const File& load(const SourceLocation& uri, const std::string& path, const std::string& identity);
  /// Reads the header (format, format_version, angle_unit, scene) as StdSceneReader does.
  void read_header(File& file);
  /// The first node named `name` under `elements` (depth-first), with the linear part (rotation
  /// and scale) of the Transform nodes above it; false when there is none.
  bool find_named(const yaml::NodeRef& elements, std::string_view name, const Eigen::Matrix3d& above,
                  yaml::NodeRef& found, Eigen::Matrix3d& found_above);
  /// The value of `key` in mapping `node`, as a reader sees it (empty when absent).
  static yaml::NodeRef value_of(const yaml::NodeRef& node, std::string_view key);

  const LoadOptions& options_;
  LoadContext& ctx_;
  std::map<std::string, File> files_;  ///< by file_identity; each file is parsed once per load
  std::vector<std::string> chain_;     ///< identities of the scene files being read, outermost first
  int& chain_depth_;                   ///< the nesting depths of the files being read, added up
  std::size_t expanded_nodes_ = 0;     ///< YAML nodes of every scene file use so far
};

}  // namespace bodyfmt::detail
