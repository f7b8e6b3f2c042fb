#pragma once
/// VRML97 primitives (Box, Sphere, Cylinder, Cone) through the project's one tessellator
/// (bodyfmt/tessellate.h): the VRML fields become a bodyfmt::Geometry, so VRML and YAML shapes
/// share vertex layout (axis +Y, centred, as Choreonoid's MeshGenerator), the division number
/// and the size checks.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/mesh.h>

#include <Eigen/Core>

#include <string_view>

namespace bodyfmt::mesh {

/// The fields of one VRML primitive node, with the VRML97 defaults (which differ from the
/// body format's: Box size 2 2 2, Sphere radius 1, Cylinder radius 1 height 2, Cone
/// bottomRadius 1 height 2). `radius` holds Cone's bottomRadius.
struct VrmlPrimitive {
  std::string_view type;  ///< "Box", "Sphere", "Cylinder" or "Cone"
  Eigen::Vector3d size = Eigen::Vector3d::Constant(2);
  double radius = 1;
  double height = 2;
  bool bottom = true;
  bool side = true;
  bool top = true;
};

/// Tessellates `primitive` with Choreonoid's default division number. Invalid sizes are
/// reported by the tessellator (`geometry-invalid-size`) at `where` and give an empty mesh.
/// `side FALSE` (Cylinder, Cone) drops the side triangles and keeps every vertex, as
/// Choreonoid's MeshGenerator does, so the bounding box is unchanged.
TriangleMesh tessellate_vrml_primitive(const VrmlPrimitive& primitive, DiagnosticSink& sink,
                                       const SourceLocation& where);

}  // namespace bodyfmt::mesh
