#pragma once
// What `bodyinfo` prints: a summary for people and the reference-comparable YAML schema of
// ../shared/corpus/README.md.

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace bodyfmt::tools {

/// The summary for people: one line per link, indented by depth.
void write_summary(std::ostream& out, const Model& model, const Derived& derived);
/// `boxes`: Choreonoid's scene-graph boxes (compute_choreonoid_bounds), which the reference
/// values were taken from.
std::string format_reference_yaml(const Model& model, const Derived& derived, const std::vector<LinkBounds>& boxes,
                                  const std::vector<Diagnostic>& diagnostics);

/// `bodyinfo --pose`: every link's world frame (X_WL), translation and row-major rotation in
/// the reference layout, printed to round-trip (17 significant digits).
std::string format_pose_yaml(const Model& model, const std::vector<Eigen::Isometry3d>& X_WL);

}  // namespace bodyfmt::tools
