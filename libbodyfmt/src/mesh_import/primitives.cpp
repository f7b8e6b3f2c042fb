#include "mesh_import/primitives.h"

#include <bodyfmt/model.h>
#include <bodyfmt/tessellate.h>

#include <algorithm>

namespace bodyfmt::mesh {

TriangleMesh tessellate_vrml_primitive(const VrmlPrimitive& p, DiagnosticSink& sink, const SourceLocation& where) {
  Geometry geometry;
  if (p.type == "Box") {
    geometry = Box{p.size};
  } else if (p.type == "Sphere") {
    geometry = Sphere{p.radius};
  } else if (p.type == "Cylinder") {
    geometry = Cylinder{p.radius, p.height, p.top, p.bottom};
  } else {
    geometry = Cone{p.radius, p.height, p.bottom};
  }
  TriangleMesh mesh = tessellate(geometry, kDefaultDivisionNumber, sink, where);
  if (!p.side && (p.type == "Cylinder" || p.type == "Cone")) {
    // Cap triangles lie in one plane y = +-h/2; side triangles span both heights (the cone's
    // reach the apex).
    const auto& v = mesh.vertices;
    mesh.triangles.erase(std::remove_if(mesh.triangles.begin(), mesh.triangles.end(),
                                        [&](const std::array<int, 3>& t) {
                                          const auto y = [&](int i) { return v[static_cast<std::size_t>(i)].y(); };
                                          return !(y(t[0]) == y(t[1]) && y(t[1]) == y(t[2]));
                                        }),
                         mesh.triangles.end());
  }
  return mesh;
}

}  // namespace bodyfmt::mesh
