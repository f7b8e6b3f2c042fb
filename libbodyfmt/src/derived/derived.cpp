#include "derived/frames_internal.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/tessellate.h>

#include <fmt/format.h>

#include <cmath>

namespace bodyfmt {

TriangleMesh compute_shape_local_mesh(const Model& model, const Shape& shape, DiagnosticSink& sink,
                                      TexCoords tex_coords) {
  TriangleMesh local;
  if (const auto* resource = geometry_if<MeshResource>(shape.geometry)) {
    if (resource->mesh >= 0 && resource->mesh < static_cast<MeshIndex>(model.meshes.size())) {
      for (const MeshPart& part : model.meshes[static_cast<std::size_t>(resource->mesh)].parts)
        append_mesh(local, part.mesh);
    }
  } else {
    local = tessellate(shape.geometry, shape.division_number, sink, shape.source, tex_coords);
  }
  return local;
}

TriangleMesh compute_shape_mesh(const Model& model, const Shape& shape, DiagnosticSink& sink) {
  TriangleMesh placed;
  append_mesh(placed, compute_shape_local_mesh(model, shape, sink), shape.X_LS);
  return placed;
}

BoundingBox transform_box(const Eigen::Affine3d& transform, const BoundingBox& box) {
  BoundingBox result;
  if (box.empty()) return result;
  for (int corner = 0; corner < 8; ++corner) {
    Eigen::Vector3d p((corner & 1) ? box.max.x() : box.min.x(), (corner & 2) ? box.max.y() : box.min.y(),
                      (corner & 4) ? box.max.z() : box.min.z());
    result.add(transform * p);
  }
  return result;
}

void GeometryAlreadyReported::report(Diagnostic d) {
  if (d.rule_id.rfind("geometry-", 0) != 0) inner_.report(std::move(d));
}

std::vector<LinkBounds> compute_choreonoid_bounds(const Model& model, DiagnosticSink& outer) {
  GeometryAlreadyReported sink(outer);
  std::vector<LinkBounds> bounds(model.links.size());
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    for (bool visual : {true, false}) {
      // Boxes in each frame's own coordinates; children are recorded after their parents,
      // so a reverse sweep folds every frame into its parent before the parent is folded.
      std::vector<BoundingBox> in_frame(link.frames.size());
      BoundingBox in_link;
      for (const Shape& shape : link.shapes) {
        if (visual ? !shape.visual : !shape.collision) continue;
        const auto* resource = geometry_if<MeshResource>(shape.geometry);
        const bool has_asset =
            resource && resource->mesh >= 0 && resource->mesh < static_cast<MeshIndex>(model.meshes.size());
        // Primitives are boxed from the vertices Choreonoid generates, Extrusion's skewed
        // cross-sections included (ExtrusionFrames::kChoreonoid).
        const BoundingBox box = has_asset ? model.meshes[static_cast<std::size_t>(resource->mesh)].scene_bounds
                                          : bounding_box(tessellate(shape.geometry, shape.division_number, sink,
                                                                    shape.source, ExtrusionFrames::kChoreonoid));
        // A shape outside every frame (a model not read from a body file: an imported URDF's)
        // is placed by its own transform; the loader gives every shape a frame.
        if (shape.frame >= 0)
          in_frame[static_cast<std::size_t>(shape.frame)].add(box);
        else
          in_link.add(transform_box(shape.X_LS, box));
      }
      for (std::size_t f = link.frames.size(); f-- > 0;) {
        const BoundingBox box = transform_box(link.frames[f].X_PF, in_frame[f]);
        const int parent = link.frames[f].parent;
        (parent >= 0 ? in_frame[static_cast<std::size_t>(parent)] : in_link).add(box);
      }
      (visual ? bounds[i].visual : bounds[i].collision) = in_link;
    }
  }
  return bounds;
}

namespace {

// The box of compute_shape_mesh(model, shape), without building that mesh: each vertex is
// placed by the same product as append_mesh's, so the box is the same to the bit. Imported
// parts are boxed one by one rather than copied into one mesh first.
BoundingBox shape_bounds(const Model& model, const Shape& shape, DiagnosticSink& sink) {
  const auto* resource = geometry_if<MeshResource>(shape.geometry);
  if (resource == nullptr) {
    return bounding_box(tessellate(shape.geometry, shape.division_number, sink, shape.source, TexCoords::kNone),
                        shape.X_LS);
  }
  BoundingBox box;
  if (resource->mesh >= 0 && resource->mesh < static_cast<MeshIndex>(model.meshes.size())) {
    for (const MeshPart& part : model.meshes[static_cast<std::size_t>(resource->mesh)].parts)
      box.add(bounding_box(part.mesh, shape.X_LS));
  }
  return box;
}

}  // namespace

std::vector<LinkBounds> compute_link_bounds(const Model& model, DiagnosticSink& outer) {
  GeometryAlreadyReported sink(outer);
  std::vector<LinkBounds> bounds(model.links.size());
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    for (const Shape& shape : model.links[i].shapes) {
      const BoundingBox box = shape_bounds(model, shape, sink);
      if (shape.visual) bounds[i].visual.add(box);
      if (shape.collision) bounds[i].collision.add(box);
    }
  }
  return bounds;
}

bool computable(const MassProperties& m) {
  return std::isfinite(m.mass) && m.center_of_mass.allFinite() && m.inertia.allFinite() &&
         m.inertia.cwiseAbs().maxCoeff() <= kLargestComputableInertia;
}

namespace {

/// The contribution of `link` with the largest `measure`, or nullptr when it has none.
template <typename Measure>
const MassContribution* largest_contribution(const Link& link, Measure measure) {
  const MassContribution* largest = nullptr;
  for (const MassContribution& c : link.mass_contributions)
    if (!largest || measure(c) > measure(*largest)) largest = &c;
  return largest;
}

// Every loaded number is finite, but sums and products of huge ones need not be: a RigidBody
// 1e306 m from its link makes the parallel-axis term infinite. Said once per link, at the
// values that combine, so that no tool writes or simulates the NaN that follows.
void report_overflow(const Model& model, const Derived& d, DiagnosticSink& sink) {
  // A far-off root can bring a world frame back into range while the root-relative one
  // overflows, so both are checked.
  const std::vector<Eigen::AffineCompact3d> X_RL = detail::compact_root_relative_frames(model);
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    const MassProperties& m = d.mass[i];
    const bool frame_finite = d.X_WL[i].matrix().allFinite() && X_RL[i].matrix().allFinite();
    if (computable(m) && frame_finite) continue;
    const bool mass_finite = std::isfinite(m.mass) && m.center_of_mass.allFinite() && m.inertia.allFinite();
    if (mass_finite && frame_finite) {  // finite, but too large to decompose
      // The culprit: the contribution with the largest own or parallel-axis term.
      const MassContribution* largest = largest_contribution(link, [](const MassContribution& c) {
        return c.inertia.cwiseAbs().maxCoeff() + std::abs(c.mass) * c.center_of_mass.squaredNorm();
      });
      report_rule(
          sink, "derived-not-finite", largest && largest->source.known() ? largest->source : link.source,
          fmt::format("the combined inertia of link \"{}\" reaches {:g} kg·m², beyond {:g}, where its principal "
                      "moments and every balanced or exported tensor overflow to infinity or NaN",
                      link.name, m.inertia.cwiseAbs().maxCoeff(), kLargestComputableInertia),
          "no body has an inertia this large (the Earth's is 8e37 kg·m²); check the exponents");
      continue;
    }
    // The culprit of an overflowing sum is the contribution farthest out.
    const MassContribution* farthest =
        largest_contribution(link, [](const MassContribution& c) { return c.center_of_mass.norm(); });
    const SourceLocation at = !mass_finite && farthest && farthest->source.known()  ? farthest->source
                              : !frame_finite && link.sources.translation().known() ? link.sources.translation()
                                                                                    : link.source;
    report_rule(sink, "derived-not-finite", at,
                fmt::format("the {} of link \"{}\" {} to infinity or NaN",
                            !mass_finite ? "combined mass properties" : "world frame", link.name,
                            !mass_finite ? "overflow" : "overflows"),
                "a translation or centre of mass this far out (beyond about 1e150 m) cannot be combined; check the "
                "exponents");
  }
}

}  // namespace

Derived compute_derived(const Model& model, DiagnosticSink& sink) {
  Derived d;
  d.mass.reserve(model.links.size());
  for (const Link& link : model.links) {
    d.mass.push_back(compute_mass_properties(link));
    d.total_mass += d.mass.back().mass;
  }
  d.X_WL = detail::compact_world_frames(model);
  report_overflow(model, d, sink);
  d.bounds = compute_link_bounds(model, sink);
  return d;
}

}  // namespace bodyfmt
