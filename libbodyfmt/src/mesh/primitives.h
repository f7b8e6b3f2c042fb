#pragma once
/// Local fallback triangulation of the VRML primitives (Box, Sphere, Cylinder, Cone), laid out
/// as Choreonoid's MeshGenerator does (axis +Y, centred, body-format-spec §9). Written before
/// the shared tessellator (bodyfmt/tessellate.h) existed; switching VRML primitives to it is a
/// follow-up (it would also give VRML the same division-number handling as YAML shapes).

#include <bodyfmt/mesh.h>

namespace bodyfmt::mesh {

constexpr int kDefaultDivisionNumber = 20;  // Choreonoid's MeshGenerator default

TriangleMesh make_box(const Eigen::Vector3d& size);
TriangleMesh make_sphere(double radius, int division = kDefaultDivisionNumber);
TriangleMesh make_cylinder(double radius, double height, bool bottom, bool side, bool top,
                           int division = kDefaultDivisionNumber);
TriangleMesh make_cone(double radius, double height, bool bottom, bool side,
                       int division = kDefaultDivisionNumber);

}  // namespace bodyfmt::mesh
