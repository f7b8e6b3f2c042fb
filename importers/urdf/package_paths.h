#pragma once
// Finding the files URDF mesh URIs name, without ROS: `package://NAME/PATH`, `file://PATH`,
// absolute and relative paths.
#include <filesystem>
#include <string>
#include <vector>

namespace bodyfmt::urdf_import {

struct MeshSearch {
  std::vector<std::string> package_paths;  ///< --package-path folders, searched first
  bool use_ros_package_path = true;        ///< then the folders of $ROS_PACKAGE_PATH
  std::filesystem::path urdf_folder;       ///< relative paths start here; package.xml is looked for from here up
};

struct MeshLookup {
  std::string path;                   ///< the file found (absolute, lexically normal); empty when none
  std::vector<std::string> searched;  ///< every place looked at, in order (for the error)
  std::string problem;                ///< why the URI cannot be looked up at all (an unknown scheme), or empty
  std::string package_folder;         ///< for package://NAME/...: the folder of package NAME it was found in
};

/// Looks for the file of `uri`. For `package://NAME/PATH`, in order: each package path P as
/// P/NAME/PATH (and as P/PATH when P's package.xml names NAME), the same for each folder of
/// ROS_PACKAGE_PATH, then every folder D from the URDF's folder up to the file system root:
/// D/PATH when D's package.xml names NAME (or, without a package.xml, D is named NAME), and
/// D/NAME/PATH when D/NAME is a folder (a sibling package in a workspace).
MeshLookup find_mesh(const std::string& uri, const MeshSearch& search);

/// The <name> of the package.xml in `folder`, or empty.
std::string package_xml_name(const std::filesystem::path& folder);

/// The folder tree a URDF came with: the nearest folder at or above `urdf_folder` holding a
/// package.xml (its package), else `urdf_folder` itself; canonical (links resolved).
std::filesystem::path urdf_tree(const std::filesystem::path& urdf_folder);

/// True when `file`, with every link resolved, lies inside the canonical folder `tree`.
bool inside_tree(const std::string& file, const std::filesystem::path& tree);

}  // namespace bodyfmt::urdf_import
