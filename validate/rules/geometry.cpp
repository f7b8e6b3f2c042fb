// Geometry rules beyond the loader's (which reports non-positive sizes, degenerate
// Extrusions/ElevationGrids, IndexedFaceSet indices and unknown types).

#include "rule_context.h"

#include <fmt/format.h>

namespace bodyfmt::validate::detail {

// body-format-spec §9: Choreonoid accepts a Box with a zero edge (only negative is an error),
// but it has no volume: MuJoCo refuses a zero geom size, Drake and Bullet build a degenerate
// collision shape. A zero scale component flattens any shape the same way.
void check_geometry(const RuleContext& ctx) {
  for (const Link& link : ctx.model.links) {
    for (const Shape& shape : link.shapes) {
      const SourceLocation at = first_known({shape.source, link.source});
      if (const auto* box = std::get_if<Box>(&shape.geometry)) {
        if ((box->size.array() == 0).any()) {
          ctx.report("geometry-zero-size", at,
                     fmt::format("Box {}of link \"{}\" has a zero edge: size {}",
                                 shape.name.empty() ? "" : "\"" + shape.name + "\" ", link.name, vec(box->size)),
                     "give every edge a positive length (a thin plate still needs a thickness)");
        }
        continue;
      }
      const Eigen::Vector3d scale = shape.X_LS.linear().colwise().norm();
      if ((scale.array() == 0).any()) {
        ctx.report(
            "geometry-zero-size", at,
            fmt::format("{} shape {}of link \"{}\" is scaled to zero: scale {}", geometry_type_name(shape.geometry),
                        shape.name.empty() ? "" : "\"" + shape.name + "\" ", link.name, vec(scale)));
      }
    }
  }
}

}  // namespace bodyfmt::validate::detail
