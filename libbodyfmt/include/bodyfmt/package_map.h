#pragma once
/// The one package map: where a `package://NAME/PATH` URI points, for every reader (the Body
/// loader, the URDF importer) and where a writer finds the ROS package it writes into (body2urdf).
/// A URI written in a .body file and in a URDF beside it resolves to the same file.
#include <bodyfmt/export.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// Where package://NAME/PATH is looked for.
struct PackageSearch {
  std::vector<std::string> package_paths;  ///< --package-path folders, searched first
  bool use_ros_package_path = true;        ///< then the folders of $ROS_PACKAGE_PATH
  /// The folder of the file that holds the URI: package.xml is looked for from here up.
  std::filesystem::path referring_folder;
};

struct PackageLookup {
  std::string path;                   ///< the file found (absolute, lexically normal); empty when none
  std::vector<std::string> searched;  ///< every place looked at, in order (for the message)
  std::string problem;                ///< why the URI names no file to look for, or empty
  std::string package_folder;         ///< the folder of package NAME the file was found in
};

/// True for `package://...`.
bool is_package_uri(std::string_view uri);

/// Looks for the regular file of `uri` (package://NAME/PATH; package:///NAME/PATH is read the
/// same way, as it occurs in the wild). In order: each package path P as P/NAME/PATH, and as
/// P/PATH when P's package.xml names NAME; the same for each folder of ROS_PACKAGE_PATH; then
/// every folder D from the referring folder up to the root: D/PATH when D's package.xml names
/// NAME (or, with no package.xml, D is named NAME), and D/NAME/PATH (a sibling package).
PackageLookup find_package_file(const std::string& uri, const PackageSearch& search);

/// The <name> the package.xml in `folder` declares (read bounded, never a FIFO), or empty.
std::string package_xml_name(const std::filesystem::path& folder);

/// The ROS package a file in `folder` belongs to: the nearest folder at or above it holding a
/// package.xml, and the name that file declares.
struct RosPackage {
  std::filesystem::path root;  ///< absolute, normalised: the folder holding package.xml
  std::string name;
};

/// nullopt with `why` set when no folder at or above `folder` holds a package.xml, or the
/// nearest one cannot be read or declares no name.
std::optional<RosPackage> find_ros_package(const std::filesystem::path& folder, std::string& why);

/// `path` (absolute) as a '/'-separated path inside the package folder `root` (what follows
/// package://NAME/), or nullopt when it is outside.
std::optional<std::string> path_in_package(const std::filesystem::path& root, const std::filesystem::path& path);

/// True when `name` can be the NAME of package://NAME/ (ROS: letters, digits, '_' and '-',
/// starting with a letter).
bool is_package_name(std::string_view name);

/// The folder tree a file came with: the nearest folder at or above `folder` holding a
/// package.xml, else `folder` itself; canonical (links resolved).
std::filesystem::path package_tree(const std::filesystem::path& folder);

/// True when `file`, with every link resolved, lies inside the canonical folder `tree`.
bool inside_tree(const std::string& file, const std::filesystem::path& tree);

}  // namespace bodyfmt
#pragma GCC visibility pop
