#pragma once
// Finding the file a URDF mesh URI names, without ROS: `package://NAME/PATH` through the
// library's package map (bodyfmt/package_map.h, shared with the Body loader), `file://PATH`,
// absolute and relative paths.
#include <bodyfmt/package_map.h>

#include <string>

namespace bodyfmt::urdf_import {

/// Looks for the file of `uri`; `search.referring_folder` is the URDF's folder, where relative
/// paths start. A scheme other than package:// and file:// is a `problem`.
PackageLookup find_mesh(const std::string& uri, const PackageSearch& search);

}  // namespace bodyfmt::urdf_import
