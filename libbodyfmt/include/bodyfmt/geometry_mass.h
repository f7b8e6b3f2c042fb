#pragma once
/// Mass properties computed from shapes (issue 39): what the Choreonoid tutorial tells users to
/// compute "using proper calculations or CAD tools". Every result is for a uniform density;
/// MassProperties::mass holds the volume at density 1.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/mesh.h>
#include <bodyfmt/model.h>

#include <optional>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// Whether the combination of a link's shapes is a solid: a triangle mesh bounds a volume only
/// when every edge is shared by triangles that run it in opposite directions as often as in the
/// same one.
struct MeshSolidity {
  int boundary_edges = 0;     ///< edges used an odd number of times: the surface has a hole
  int misoriented_edges = 0;  ///< edges run the same way by two triangles: normals disagree
  bool solid() const { return boundary_edges == 0 && misoriented_edges == 0; }
};

/// Vertices are compared by position (tessellated and imported meshes repeat them per face).
MeshSolidity mesh_solidity(const TriangleMesh& mesh);

/// Volume, centroid and inertia about the centroid (density 1) of the solid that a closed mesh
/// bounds, by the divergence theorem over its triangles (each with the origin as a tetrahedron).
/// An inside-out mesh gives its volume positive. Meaningful only when mesh_solidity() is solid.
MassProperties mesh_mass_properties(const TriangleMesh& mesh);

/// Closed forms in the shape's own frame (body-format-spec §9, axes as the tessellator's: the
/// Cylinder, Cone and Capsule axis is +Y, the Cone's apex at +h/2): Box, Sphere, Cylinder with
/// both caps, Cone with its bottom, Capsule. nullopt for every other geometry, an open
/// primitive, or sizes the loader has already refused.
std::optional<MassProperties> primitive_mass_properties(const Geometry& geometry);

/// `mass` moved by an affine map (rotation, translation and any scale, mirrored or not): the
/// second moments transform as A·Σ·Aᵀ·|det A|, the volume by |det A|.
MassProperties transform_mass_properties(const MassProperties& mass, const Eigen::Affine3d& transform);

/// `mass` (density 1) at `density`.
MassProperties at_density(const MassProperties& mass, double density);

/// The mass properties (density 1) of one shape in its link's frame, through Shape::X_LS
/// (nested Transforms and scale included). nullopt when the shape is no solid: reports
/// `mass-geometry-not-solid` at the shape (at the `uri` of a mesh file) and leaves it out.
std::optional<MassProperties> shape_mass_properties(const Model& model, const Shape& shape, DiagnosticSink& sink);

/// The innermost RigidBody element above `shape` in its link's element tree: its index in
/// Link::mass_contributions, or -1 when the shape is below none.
int enclosing_rigid_body(const Link& link, const Shape& shape);

/// The pose of the element frame `frame` (an index into Link::frames) in its link's frame.
Eigen::Affine3d frame_in_link(const Link& link, int frame);

/// A link's solid geometry at density 1: its collision shapes, or its visual ones when it has
/// no collision shape (a plain Shape is both; Choreonoid's Visual and Collision elements make
/// one of each). A RigidBody element's mass data is that of the shapes below it: they count for
/// it, not for the link-level keys, and never twice (body-format-spec §6.4: shapes carry no mass
/// in Choreonoid; a RigidBody around them is how a file gives them one).
struct RigidBodyGeometry {
  std::size_t contribution = 0;                                                ///< in Link::mass_contributions
  MassProperties volume{0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()};  ///< density 1, link frame
  int solids = 0;
  int left_out = 0;
  bool empty() const { return solids == 0 || !(volume.mass > 0); }
};
struct LinkGeometryMass {
  /// The shapes below no RigidBody element (what the link-level keys stand for), density 1.
  MassProperties volume{0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()};
  int solids = 0;                               ///< shapes below no RigidBody that contributed
  int left_out = 0;                             ///< shapes that are no solid (reported), anywhere in the link
  bool from_visual = false;                     ///< the link has no collision shape
  std::vector<RigidBodyGeometry> rigid_bodies;  ///< each RigidBody element with shapes below it
  /// No solid outside the RigidBody elements.
  bool empty() const { return solids == 0 || !(volume.mass > 0); }
  /// Shapes below RigidBody elements that contributed.
  int solids_in_rigid_bodies() const;
  /// No solid anywhere in the link.
  bool no_solid() const { return empty() && solids_in_rigid_bodies() == 0; }
};
LinkGeometryMass link_geometry_mass(const Model& model, const Link& link, DiagnosticSink& sink);

/// The combination of contributions (body-format-spec §6.4): total mass, mass-weighted centre,
/// inertias moved to it by the parallel-axis theorem; a massless sum drops the inertias.
/// compute_mass_properties() is this over a link's contributions.
MassProperties combine_mass_contributions(const std::vector<MassContribution>& contributions);

/// A link's mass properties with the shapes outside its RigidBody elements at `density` in place
/// of its link-level keys (the keys stay when there are no such shapes), combined with its
/// RigidBody elements as written (each stands for the shapes below it). nullopt when the link has
/// no solid geometry at all.
std::optional<MassProperties> link_mass_from_geometry(const Link& link, const LinkGeometryMass& geometry,
                                                      double density);

/// The geometry scaled to `mass` (the density that gives it): what the link-level keys would
/// hold (centre of mass and inertia about it) for the link's written mass.
std::optional<MassProperties> geometry_at_mass(const LinkGeometryMass& geometry, double mass);

/// A RigidBody element's centre of mass and inertia recomputed from the shapes below it at its
/// written mass.
struct RecomputedRigidBody {
  std::size_t contribution = 0;  ///< in Link::mass_contributions
  MassProperties in_link;        ///< link frame, as the contribution holds it
  MassProperties as_written;     ///< in the element's own frame, as its keys are written
};

/// Every part of a link's mass data recomputed from the shapes it stands for, each at its written
/// mass: the link-level keys from the shapes below no RigidBody element (when the link has a
/// link-level `mass` and such shapes), each RigidBody element from the shapes below it (when it
/// has some and a positive mass), and the link's combination then. nullopt when nothing can be
/// recomputed.
struct GeometryAtWrittenMass {
  std::optional<MassProperties> link_keys;        ///< the `mass`, `center_of_mass` and `inertia` to write
  std::vector<RecomputedRigidBody> rigid_bodies;  ///< the RigidBody elements recomputed
  MassProperties combined;                        ///< the link's mass properties then
};
std::optional<GeometryAtWrittenMass> geometry_at_written_mass(const Link& link, const LinkGeometryMass& geometry);

}  // namespace bodyfmt
#pragma GCC visibility pop
