#pragma once
// Contact points of a model: the vertices of every collision shape, tessellated once by the
// shared tessellator (compute_shape_mesh), in their link's frame.

#include <bodyfmt/dynamics/simulation.h>

#include <vector>

namespace bodyfmt::dynamics {

/// Per link, the distinct vertices of its collision shapes. A link with more than
/// kMaxPointsPerLink distinct vertices keeps the extreme vertex along each of that many
/// evenly spread directions (its support points), which is what can touch a flat floor.
constexpr int kMaxPointsPerLink = 256;
std::vector<ContactPoint> collect_contact_points(const Model& model, DiagnosticSink& sink);

}  // namespace bodyfmt::dynamics
