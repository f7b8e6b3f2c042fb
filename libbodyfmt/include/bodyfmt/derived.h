#pragma once
/// Data derived from a Model once and shared by validators, writers and the dynamics checker.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>
#include <bodyfmt/tessellate.h>

#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// Combines a link's rigid-body contributions (body-format-spec §6.4): total mass, centre
/// of mass in the link frame, inertia about the centre of mass in link axes. A link with no
/// contribution gets Choreonoid's defaults (1 kg, origin, identity inertia).
MassProperties compute_mass_properties(const Link& link);

/// Largest combined inertia entry whose principal decomposition (ours, and MuJoCo's of a
/// fullinertia) does not overflow, although every entry is finite.
inline constexpr double kLargestComputableInertia = 1e100;

/// Finite, with an inertia within kLargestComputableInertia. compute_derived reports every
/// link that is not (derived-not-finite); rules that decompose the inertia skip those links.
bool computable(const MassProperties& mass);

/// Link frames at the given joint positions (one per link, indexed like Model::links; joints
/// without an entry are at 0). X_RL: link frame relative to the root link frame.
std::vector<Eigen::Isometry3d> compute_root_relative_frames(const Model& model, const std::vector<double>& q = {});
/// X_WL: link frames in the world, the root placed at its initial pose from the file.
std::vector<Eigen::Isometry3d> compute_world_frames(const Model& model, const std::vector<double>& q = {});

/// The one way to keep a geometry problem from being reported twice: the loader validates
/// every shape's parameters and reports problems at the exact key, and whatever tessellates
/// the shapes again (bounds, exporters) reports through this sink, which drops `geometry-*`
/// findings and forwards everything else.
class GeometryAlreadyReported : public DiagnosticSink {
 public:
  explicit GeometryAlreadyReported(DiagnosticSink& inner) : inner_(inner) {}
  void report(Diagnostic d) override;

 private:
  DiagnosticSink& inner_;
};

/// Triangle mesh of one shape in its own frame (before Shape::X_LS): tessellated primitives
/// or the imported mesh parts.
/// `tex_coords` as in tessellate(); imported meshes keep what their file gives.
TriangleMesh compute_shape_local_mesh(const Model& model, const Shape& shape, DiagnosticSink& sink,
                                      TexCoords tex_coords = TexCoords::kNone);
/// The same, placed in its link's frame.
TriangleMesh compute_shape_mesh(const Model& model, const Shape& shape, DiagnosticSink& sink);

struct LinkBounds {
  BoundingBox visual;     ///< link frame; empty when the link has no visual geometry
  BoundingBox collision;  ///< link frame
};

/// Tight bounding boxes of each link's visual and collision geometry in the link frame.
std::vector<LinkBounds> compute_link_bounds(const Model& model, DiagnosticSink& sink);

/// The boxes Choreonoid's scene graph reports: a group's box is the union of its children's,
/// a transform's box is the axis-aligned box of its transformed child box, so nested
/// rotations inflate it. Only for comparison with Choreonoid (bodyinfo --format yaml);
/// everything else uses the tight boxes.
std::vector<LinkBounds> compute_choreonoid_bounds(const Model& model, DiagnosticSink& sink);

/// The axis-aligned box of `box` transformed (its 8 corners).
BoundingBox transform_box(const Eigen::Affine3d& transform, const BoundingBox& box);

/// Everything above that every consumer reads, computed once. Root-relative frames are not kept
/// (a large model would carry 128 bytes per link for the few readers of them): those call
/// compute_root_relative_frames().
struct Derived {
  std::vector<MassProperties> mass;
  /// World link frames at zero joint positions, in the 3x4 storage of Link::X_PL (with a
  /// point, use as_isometry(), as compute_world_frames gives them).
  std::vector<Eigen::AffineCompact3d> X_WL;
  std::vector<LinkBounds> bounds;  ///< tight
  double total_mass = 0;
};

Derived compute_derived(const Model& model, DiagnosticSink& sink);

}  // namespace bodyfmt
#pragma GCC visibility pop
