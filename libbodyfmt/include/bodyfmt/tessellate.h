#pragma once
/// The project's one tessellator: Geometry (body-format-spec §9) -> TriangleMesh.
///
/// Meshes follow Choreonoid's MeshGenerator conventions (vertex placement, division rules) so
/// that exported meshes match what Choreonoid renders, with one deliberate difference: every
/// triangle is counter-clockwise seen from outside (signed_volume() > 0 for closed solids),
/// also where Choreonoid would produce an inside-out Extrusion.
///
/// Invalid parameters are reported to the sink (rules `geometry-invalid-size`,
/// `geometry-degenerate`, `geometry-index-out-of-range`) and give an empty or partial mesh.
/// Nothing here throws, prints or aborts.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/mesh.h>
#include <bodyfmt/model.h>

#include <Eigen/Core>

#include <array>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// How an Extrusion's cross-sections are placed where Choreonoid's MeshGenerator does not
/// build a rotation. A spine whose points are all collinear is turned by Choreonoid with the
/// axis-angle formula applied to the axis +Y x dir left unnormalised (its length is
/// sin(angle)): for a spine along a coordinate axis that is a rotation, for any other
/// direction the cross-section is shrunk and skewed, and for a spine along -Y it is -I, a
/// reflection. Elsewhere its cross-section plane takes the spine's Z axis as it is, without
/// making it perpendicular to the spine tangent, only an exactly zero Z counts as collinear,
/// and an `orientation` axis is used as written, not normalised.
enum class ExtrusionFrames {
  /// Proper rotations (the meshes every exporter writes: the cross-section keeps its shape).
  kRigid,
  /// Choreonoid's matrices, distortion and reflection included: the vertices Choreonoid
  /// generates, for reproducing the boxes it reports (compute_choreonoid_bounds). The
  /// triangles are still made to face outward for closed solids.
  kChoreonoid,
};

/// Choreonoid's default circle division (body-format-spec §9).
constexpr int kDefaultDivisionNumber = 20;
/// Upper bound applied by the tessellator so that a huge `division_number` cannot exhaust
/// memory (a sphere has about n^2 / 2 vertices). Larger values are clamped with a warning.
constexpr int kMaxDivisionNumber = 1024;

/// `division_number` as Choreonoid uses it: values < 4 mean the default 20.
/// (Not clamped to kMaxDivisionNumber; tessellate() does that and reports it.)
int effective_division_number(int division_number);

/// Whether tessellate() adds texture coordinates. Only textured shapes ask for them: the
/// vertices are split along texture seams, so the mesh differs from the untextured one.
enum class TexCoords { kNone, kGenerate };

/// Triangulates `geometry` in the shape's local frame (before Shape::X_LS).
///
/// * Box: centred, full edge lengths. Sphere: centred, n longitudes x n/2 latitude bands.
/// * Cylinder, Cone, Capsule: axis +Y, centred; circle vertex i at angle 2 pi i / n measured
///   from +X towards +Z, i.e. (r cos a, y, r sin a). Cone base at y = -h/2, apex at +h/2.
///   Capsule `height` is the cylindrical part; the caps are hemispheres.
/// * Extrusion: VRML97 (spine-aligned cross-section planes), as Choreonoid's MeshGenerator.
/// * ElevationGrid: vertex (i, j) at (i x_spacing, height[j x_dimension + i], j z_spacing).
/// * IndexedFaceSet: polygons terminated by -1 (a trailing polygon without -1 is dropped, as
///   Choreonoid does), triangulated by ear clipping. TriangleMeshGeometry: flat triangles.
/// * MeshResource: empty (meshes are imported elsewhere).
///
/// Normals are left empty (see with_vertex_normals()). Texture coordinates are empty unless
/// `tex_coords` is kGenerate; then every vertex gets one, by Choreonoid's MeshGenerator
/// conventions (VRML97), and vertices are duplicated where one position needs two:
/// * Box: each face maps the whole image, upright seen from outside (top: +X right, -Z up).
/// * Sphere, Cylinder side, Cone side, Capsule: u runs around the Y axis, 0 at -Z, through -X,
///   +Z (0.5) and +X; v runs from 0 at the bottom to 1 at the top (Capsule: over its whole
///   height). Where the division number does not put a vertex at -Z, the triangle across the
///   seam gets u slightly above 1 (drawn right with repeat_s, the default). A pole or apex
///   corner takes the mean u of its triangle's other two corners.
/// * Cylinder and Cone caps: the disc inscribed in the image, (0.5 + 0.5 cos a, 0.5 -+ 0.5 sin a)
///   at circle angle a (top cap minus, bottom plus).
/// * ElevationGrid: u = i / (x_dimension - 1), v = j / (z_dimension - 1).
/// * IndexedFaceSet, TriangleMeshGeometry: their tex_coords via tex_coord_indices (or via the
///   vertex indices when those are empty); without tex_coords the VRML97 default, which
///   projects onto the two largest extents of the bounding box (u 0..1 along the largest, v at
///   the same scale). Indices out of range give no texture coordinates at all.
/// * Extrusion sides: u the length along the cross-section, v along the spine, as fractions
///   of the whole; caps: the cross-section's bounding box stretched to the image, the end cap
///   mirrored in u.
///
/// `frames` matters for Extrusion only (see ExtrusionFrames); the overload without it is kRigid.
/// It generates no texture coordinates (it serves Choreonoid's bounding boxes).
TriangleMesh tessellate(const Geometry& geometry, int division_number, DiagnosticSink& sink,
                        const SourceLocation& where, ExtrusionFrames frames);
TriangleMesh tessellate(const Geometry& geometry, int division_number, DiagnosticSink& sink,
                        const SourceLocation& where, TexCoords tex_coords = TexCoords::kNone);

/// tessellate(shape.geometry, shape.division_number, sink, shape.source, tex_coords).
TriangleMesh tessellate(const Shape& shape, DiagnosticSink& sink, TexCoords tex_coords = TexCoords::kNone);

/// A copy of `mesh` with per-vertex normals by the VRML97 creaseAngle rule: at each corner,
/// the normal averages (area-weighted) the normals of the faces around the vertex that differ
/// from the corner's own face by at most `crease_angle` radians; 0 gives flat shading, >= pi
/// smooths everything. Vertices are split where corners get different normals, so the result
/// may have more vertices than `mesh`; vertices no triangle uses are dropped, and so are
/// triangles with out-of-range indices. Triangles otherwise keep their order and winding.
/// Existing normals are replaced; texture coordinates follow their vertex. With texture
/// coordinates, vertices at the same position are smoothed as one (a texture seam is no
/// shading seam); without them, only by index, as before.
TriangleMesh with_vertex_normals(const TriangleMesh& mesh, double crease_angle);

/// Triangulates one polygon given as indices into `vertices` (all indices must be valid) by
/// ear clipping on its projection onto the plane of its Newell normal. Consecutive duplicate
/// points are ignored. The triangles keep the polygon's winding and are appended to
/// `triangles`. Returns false, appending nothing, for a degenerate polygon: fewer than three
/// distinct points or no area. A self-intersecting polygon still yields triangles covering it
/// approximately. Useful for mesh importers (OBJ, VRML faces) too. The work is bounded: a
/// polygon that would take more than about 4·10⁸ point tests (a self-intersecting polygon of
/// thousands of corners) yields nothing and sets `*over_budget`.
bool triangulate_polygon(const std::vector<Eigen::Vector3d>& vertices, const std::vector<int>& polygon,
                         std::vector<std::array<int, 3>>& triangles, bool* over_budget = nullptr);

}  // namespace bodyfmt
#pragma GCC visibility pop
