#include <bodyfmt/derived.h>
#include <bodyfmt/tessellate.h>

namespace bodyfmt {

TriangleMesh compute_shape_mesh(const Model& model, const Shape& shape, DiagnosticSink& sink) {
  TriangleMesh local;
  if (const auto* resource = std::get_if<MeshResource>(&shape.geometry)) {
    if (resource->mesh >= 0 && resource->mesh < static_cast<MeshIndex>(model.meshes.size())) {
      for (const MeshPart& part : model.meshes[static_cast<std::size_t>(resource->mesh)].parts)
        append_mesh(local, part.mesh);
    }
  } else {
    local = tessellate(shape.geometry, shape.division_number, sink, shape.source);
  }
  TriangleMesh placed;
  append_mesh(placed, local, shape.X_LS);
  return placed;
}

std::vector<LinkBounds> compute_link_bounds(const Model& model, DiagnosticSink& sink) {
  std::vector<LinkBounds> bounds(model.links.size());
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    for (const Shape& shape : model.links[i].shapes) {
      const BoundingBox box = bounding_box(compute_shape_mesh(model, shape, sink));
      if (shape.visual) bounds[i].visual.add(box);
      if (shape.collision) bounds[i].collision.add(box);
    }
  }
  return bounds;
}

Derived compute_derived(const Model& model, DiagnosticSink& sink) {
  Derived d;
  d.mass.reserve(model.links.size());
  for (const Link& link : model.links) {
    d.mass.push_back(compute_mass_properties(link));
    d.total_mass += d.mass.back().mass;
  }
  d.X_RL = compute_root_relative_frames(model);
  d.X_WL = compute_world_frames(model);
  d.bounds = compute_link_bounds(model, sink);
  return d;
}

}  // namespace bodyfmt
