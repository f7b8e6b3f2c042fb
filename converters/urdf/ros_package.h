#pragma once
/// The ROS package a URDF is written into: the nearest folder at or above the output's folder
/// that holds a package.xml, and the package name that file declares. `package://NAME/PATH`
/// URIs are relative to that folder (as ROS resolves them), not to the URDF's own folder.
#include <filesystem>
#include <optional>
#include <string>

namespace bodyfmt::urdf {

struct RosPackage {
  std::filesystem::path root;  ///< absolute, normalised: the folder holding package.xml
  std::string name;            ///< the <name> package.xml declares
};

/// Looks for package.xml from `start` (a folder) upwards. nullopt with `why` set when there is
/// none, or when it cannot be read or declares no name.
std::optional<RosPackage> find_ros_package(const std::filesystem::path& start, std::string& why);

/// `path` (absolute) as a path inside the package folder `root`, '/'-separated (what follows
/// `package://NAME/`); nullopt when it is outside.
std::optional<std::string> path_in_package(const std::filesystem::path& root, const std::filesystem::path& path);

}  // namespace bodyfmt::urdf
