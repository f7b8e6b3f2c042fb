#pragma once
// What `bodyinfo` prints: a summary for people and the reference-comparable YAML schema of
// ../shared/corpus/README.md.

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <string>
#include <vector>

namespace bodyfmt::tools {

std::string format_summary(const Model& model, const Derived& derived);
/// `boxes`: Choreonoid's scene-graph boxes (compute_choreonoid_bounds), which the reference
/// values were taken from.
std::string format_reference_yaml(const Model& model, const Derived& derived, const std::vector<LinkBounds>& boxes,
                                  const std::vector<Diagnostic>& diagnostics);

}  // namespace bodyfmt::tools
