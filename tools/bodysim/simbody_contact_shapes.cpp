#include "simbody_contact_shapes.h"

#include <bodyfmt/rules.h>

#include <fmt/format.h>

namespace bodyfmt::tools {

bool simbody_takes_contact_shapes(const Model& model, DiagnosticSink& sink) {
  // Simbody's elastic-foundation meshes did not finish 1 simulated second of SimpleTank (its
  // Extrusion tracks) in 10 CPU minutes: until that is understood, --contact simbody takes
  // Box collision shapes (Bricks) only, rather than hang.
  for (const Link& link : model.links)
    for (const Shape& shape : link.shapes)
      if (shape.collision && !std::holds_alternative<Box>(shape.geometry)) {
        report_rule(sink, "dynamics-contact-geometry", shape.source,
                    fmt::format("--contact simbody takes Box collision shapes only (as Bricks); this {} of link "
                                "\"{}\" would be an elastic-foundation mesh, which does not finish in "
                                "reasonable time",
                                geometry_type_name(shape.geometry), link.name),
                    "use the default --contact points");
        return false;
      }
  return true;
}

}  // namespace bodyfmt::tools
