#pragma once
/// Reading a URDF into a bodyfmt Model (the urdf2body importer). What maps and what is
/// reported lost is listed in converters/urdf/IMPORT.md.
///
/// Every diagnostic points at the URDF line and column of the element or attribute
/// responsible (columns are found in the text; see xml_positions.h). Located errors:
/// `import-syntax` (not well-formed XML, not a <robot>), `import-structure` (a joint naming a
/// missing link, two roots, a cycle, a link with two parent joints, duplicate names, a missing
/// required element or attribute), `import-value` (a number or vector that does not read, an
/// unknown joint type, a zero axis), `import-mass` (a negative mass or inertia diagonal),
/// `import-mesh` (a mesh that cannot be found: the URI and every place searched). Constructs a
/// .body cannot hold are reported as `export-loss` with their kind (converters/core: loss.h),
/// so that `--strict` and `--allow-loss` treat them as the exporters' losses.
///
/// Where Choreonoid's URDF loader reads a URDF otherwise than the URDF spec (IMPORT.md, "Two
/// readings"), UrdfImportOptions::semantics chooses: urdf2body keeps the URDF meaning with an
/// `import-choreonoid-differs` note at each place; a wrapper body file takes Choreonoid's with a
/// warning (`wrapper-urdf-mass`, `wrapper-urdf-world`, `wrapper-urdf-semantics`), and what that
/// loader refuses is `wrapper-urdf-refused`.
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::urdf_import {

/// Whose reading of a URDF the model takes where two consumers differ (IMPORT.md, "Two readings").
enum class UrdfSemantics {
  /// The URDF spec's, as urdfdom and ROS tools read it: urdf2body writes a new model with this
  /// meaning (a link without <inertial> is a massless frame, a root `world` link fixes the base)
  /// and notes each place where Choreonoid's URDF loader reads the same text differently
  /// (`import-choreonoid-differs`).
  kUrdf,
  /// Choreonoid's URDF loader's (src/URDFBodyLoader): a wrapper body file is a Body file, so it
  /// loads link for link as Choreonoid loads it, each difference a warning at its URDF line.
  kChoreonoid,
};

struct UrdfImportOptions {
  UrdfSemantics semantics = UrdfSemantics::kUrdf;
  /// Roots for `package://NAME/...` URIs, searched before ROS_PACKAGE_PATH.
  std::vector<std::string> package_paths;
  bool use_ros_package_path = true;
  /// The folder of the .body file to be written: mesh URIs are written relative to it.
  std::filesystem::path output_folder = ".";
  /// Look meshes up (false: keep each URI as written, unresolved).
  bool resolve_meshes = true;
  /// Accept only meshes inside the URDF's folder tree (its package: the nearest folder at or
  /// above the URDF with a package.xml, else the URDF's folder) or inside the package a
  /// package:// URI names; any other file (an absolute path, "../..", a link out of the tree)
  /// is an `import-mesh` error. urdf2body --copy-meshes sets it: a downloaded URDF must not
  /// make the tool copy /etc/shadow beside the model (issue 34).
  bool confine_meshes = false;
};

/// The model of the URDF `text` (`file_name` is used in locations and to resolve relative
/// mesh paths). Links are in depth-first order from the root, children in the document order
/// of their joints; joint ids follow the document order of the movable joints. Returns
/// nullopt only when no tree can be built (malformed XML, no <robot>, no links, no root);
/// otherwise the model comes back even after errors, which are reported to `sink`.
std::optional<Model> import_urdf(std::string_view text, const std::string& file_name, const UrdfImportOptions& options,
                                 DiagnosticSink& sink);

}  // namespace bodyfmt::urdf_import
