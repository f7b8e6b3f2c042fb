#pragma once
/// How one shape is written by a target: as primitives the target has, as tessellated or
/// converted meshes, or as the mesh file it references, with the losses to report. The URDF
/// and MJCF writers both ask plan_shape() and only spell out its answer in their format.
#include <bodyfmt/converters/loss.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::converters {

/// What a target can express. Targets run their cylinders and capsules along +Z (a Body shape
/// runs along +Y, body-format-spec §19), so plan_shape turns those.
struct ShapeTarget {
  std::string_view name;  ///< in hints: "URDF cylinders are closed", "URDF materials have ..."
  bool capsule = false;   ///< has a capsule primitive (else a capsule is tessellated, no loss)
  /// > 0: the target refuses a box with a zero edge; every half edge of such a box is raised to
  /// at least this, reported.
  double min_box_half_edge = 0;
  /// Collides with convex hulls: a mesh that spans no volume loses its collision geometry.
  bool hull_collision = false;
  bool emissive_color = true;  ///< materials have an emissive colour
  /// Whether a mesh file can be referenced as it is (else its parts are written as meshes);
  /// asked only when the shape's placement is a rotation and a scale.
  std::function<bool(const MeshResource&)> references_mesh_file;
};

struct PlannedLoss {
  LossKind kind;
  SourceLocation at;
  std::string what;
  std::string hint;
};

/// One piece of a shape: a primitive, a mesh to stage, or a mesh file referenced as it is.
struct PlannedPiece {
  enum class Kind { kBox, kSphere, kCylinder, kCapsule, kMesh, kMeshFile };
  Kind kind = Kind::kMesh;
  /// The piece's frame in the link frame (target axes: a cylinder or capsule runs along +Z);
  /// a rotation and a translation only.
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< box edges
  double radius = 0;                               ///< sphere, cylinder, capsule
  /// Cylinder: its length; capsule: the length of its straight part.
  double length = 0;
  /// kMesh: the vertices to write (linear part baked in when it shears or mirrors), staged once
  /// per `key` under a name from `stem`.
  std::shared_ptr<const TriangleMesh> mesh;
  std::string key;
  std::string stem;
  /// kMesh, kMeshFile: the scale the target applies to the file's vertices.
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  const MeshResource* file = nullptr;  ///< kMeshFile: the resource referenced
  std::optional<Material> material;
  /// ShapeTarget::hull_collision, a collision shape whose mesh spans no volume: the collision
  /// geometry is dropped, and this is reported where the piece is written.
  std::optional<PlannedLoss> collision_dropped;
};

struct ShapePlan {
  std::vector<PlannedLoss> losses;  ///< in the order they are to be reported, before the pieces
  std::vector<PlannedPiece> pieces;
};

/// The colour and opacity of `material` as fractions (appearance-value-range reports values
/// outside 0..1; the targets get them clamped).
Eigen::Vector4d clamped_rgba(const Material& material);

/// The names of the materials an export writes ("material_0", "material_1", ... in first-use
/// order), one per `key`: what makes two materials the same in the target.
template <typename Value>
class MaterialNames {
 public:
  /// The name of the material with this key; a new one is recorded with `value`.
  std::string name(const std::string& key, const Value& value) {
    auto it = by_key_.find(key);
    if (it != by_key_.end()) return it->second;
    std::string name = "material_" + std::to_string(named_.size());
    named_.emplace_back(name, value);
    by_key_.emplace(key, name);
    return name;
  }
  /// (name, value) in first-use order.
  const std::vector<std::pair<std::string, Value>>& named() const { return named_; }

 private:
  std::vector<std::pair<std::string, Value>> named_;
  std::map<std::string, std::string> by_key_;
};

/// The plan for shape `shape_index` of link `link_index`. Tessellation findings the validator
/// reports already (geometry-*) are not reported again to `sink`.
ShapePlan plan_shape(const Model& model, std::size_t link_index, std::size_t shape_index, const ShapeTarget& target,
                     DiagnosticSink& sink);

}  // namespace bodyfmt::converters
