#include <bodyfmt/converters/shape_plan.h>

#include <bodyfmt/angles.h>

#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/converters/transforms.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/mesh.h>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <filesystem>
#include <limits>

namespace bodyfmt::converters {
namespace {

/// Whether qhull can build the convex hull a target collides with: at least 4 distinct points
/// that span three dimensions (a flat or sliver mesh fails with "qhull error"). Only corners
/// of triangles count: the mesh file holds no others, whatever the model's vertex list has.
bool spans_volume(const TriangleMesh& mesh) {
  std::vector<char> used(mesh.vertices.size(), 0);
  std::vector<Eigen::Vector3d> points;
  for (const auto& triangle : mesh.triangles)
    for (int i : triangle)
      if (!used[i]) {
        used[i] = 1;
        points.push_back(mesh.vertices[i]);
      }
  if (points.size() < 4) return false;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& v : points) mean += v;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& v : points) covariance += (v - mean) * (v - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d hi = -lo;
  for (const auto& v : points) {
    const Eigen::Vector3d p = solver.eigenvectors().transpose() * (v - mean);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d extent = hi - lo;
  return extent.minCoeff() > 1e-6 * extent.maxCoeff() && extent.maxCoeff() > 1e-9;
}

/// A mesh that the plan does not own (a part of the model's imported mesh).
std::shared_ptr<const TriangleMesh> borrowed(const TriangleMesh& mesh) {
  return std::shared_ptr<const TriangleMesh>(std::shared_ptr<const TriangleMesh>(), &mesh);
}

class Planner {
 public:
  Planner(const Model& model, std::size_t link_index, std::size_t shape_index, const ShapeTarget& target,
          DiagnosticSink& sink)
      : model_(model),
        link_(model.links[link_index]),
        shape_(link_.shapes[shape_index]),
        target_(target),
        sink_(sink),
        material_(shape_.appearance.material),
        sr_(decompose(shape_.X_LS.linear())),
        link_index_(link_index),
        shape_index_(shape_index) {}

  ShapePlan plan();

 private:
  void loss(LossKind kind, std::string what, std::string hint = {}) { loss_at(shape_.source, kind, what, hint); }
  void loss_at(const SourceLocation& at, LossKind kind, std::string what, std::string hint = {}) {
    plan_.losses.push_back({kind, at.known() ? at : shape_.source, std::move(what), std::move(hint)});
  }
  void geometry();
  void mesh_resource(const MeshResource& res);
  void tessellated(bool report_scale);
  void primitive(PlannedPiece::Kind kind, const Eigen::Matrix3d& turn, PlannedPiece piece);
  void mesh_piece(std::shared_ptr<const TriangleMesh> mesh, std::string key, std::string stem,
                  const std::optional<Material>& material);
  // Only meshes need these: a model of many primitives does not format them.
  std::string shape_key() const { return fmt::format("shape:{}:{}", link_index_, shape_index_); }
  std::string stem() const {
    return fmt::format("{}_{}", link_.name,
                       shape_.name.empty() ? fmt::format("shape{}", shape_index_) : shape_.name.str());
  }
  bool uniform() const {
    return sr_ && nearly_equal(sr_->scale.x(), sr_->scale.y()) && nearly_equal(sr_->scale.x(), sr_->scale.z());
  }

  const Model& model_;
  const Link& link_;
  const Shape& shape_;
  const ShapeTarget& target_;
  DiagnosticSink& sink_;
  const std::optional<Material> material_;
  const std::optional<ScaledRotation> sr_;
  const std::size_t link_index_;
  const std::size_t shape_index_;
  ShapePlan plan_;
};

ShapePlan Planner::plan() {
  const Appearance& appearance = shape_.appearance;
  if (appearance.texture)
    loss(LossKind::kTextures, fmt::format("the texture '{}'", appearance.texture->uri), "colours are kept");
  if (!target_.emissive_color && appearance.material && !appearance.material->emissive_color.isZero(0))
    loss_at(appearance.material->emissive_source, LossKind::kMaterials, "an emissive colour",
            fmt::format("{} materials have one rgba colour", target_.name));
  if (shape_.visual || shape_.collision) geometry();
  return std::move(plan_);
}

void Planner::geometry() {
  const Geometry& g = shape_.geometry;
  // Rx(-90°) maps a target's +Z axis onto the Body's +Y exactly (Choreonoid's URDF importer
  // uses +90°; the shapes are symmetric).
  const Eigen::Matrix3d z_to_y = Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  PlannedPiece piece;
  if (const auto* box = geometry_if<Box>(g); box && sr_) {
    piece.size = box->size.cwiseProduct(sr_->scale);
    const Eigen::Vector3d half = piece.size / 2;
    if (target_.min_box_half_edge > 0 && (half.array() <= 0).any()) {
      // A flat box is Choreonoid's stand-in for a plane: it gets a thickness no contact can
      // tell apart.
      piece.size = 2 * half.cwiseMax(target_.min_box_half_edge);
      loss(LossKind::kGeometry,
           fmt::format("a box with a zero edge (written with edges {})", format_vector(piece.size)),
           fmt::format("{} geoms need positive sizes", target_.name));
    }
    primitive(PlannedPiece::Kind::kBox, Eigen::Matrix3d::Identity(), std::move(piece));
  } else if (const auto* sphere = geometry_if<Sphere>(g)) {
    if (!uniform()) return tessellated(true);
    piece.radius = sphere->radius * sr_->scale.x();
    primitive(PlannedPiece::Kind::kSphere, Eigen::Matrix3d::Identity(), std::move(piece));
  } else if (const auto* cylinder = geometry_if<Cylinder>(g)) {
    if (!sr_ || !nearly_equal(sr_->scale.x(), sr_->scale.z())) return tessellated(true);
    if (!cylinder->top || !cylinder->bottom)
      loss(LossKind::kGeometry, "a cylinder without its top or bottom cap",
           fmt::format("{} cylinders are closed", target_.name));
    piece.radius = cylinder->radius * sr_->scale.x();
    piece.length = cylinder->height * sr_->scale.y();
    primitive(PlannedPiece::Kind::kCylinder, z_to_y, std::move(piece));
  } else if (const auto* capsule = geometry_if<Capsule>(g); capsule && target_.capsule) {
    if (!uniform()) return tessellated(true);
    piece.radius = capsule->radius * sr_->scale.x();
    piece.length = capsule->height * sr_->scale.x();
    primitive(PlannedPiece::Kind::kCapsule, z_to_y, std::move(piece));
  } else if (const auto* res = geometry_if<MeshResource>(g)) {
    mesh_resource(*res);
  } else {
    // Other geometry (and a box that shears) is a mesh in every target: nothing is lost.
    tessellated(false);
  }
}

void Planner::primitive(PlannedPiece::Kind kind, const Eigen::Matrix3d& turn, PlannedPiece piece) {
  piece.kind = kind;
  piece.origin.linear() = sr_->rotation * turn;
  piece.origin.translation() = shape_.X_LS.translation();
  piece.material = material_;
  plan_.pieces.push_back(std::move(piece));
}

void Planner::tessellated(bool report_scale) {
  if (report_scale)
    loss(LossKind::kGeometry,
         fmt::format("a non-uniformly scaled {} as a primitive", geometry_type_name(shape_.geometry)),
         "written as a tessellated mesh");
  GeometryAlreadyReported filtered(sink_);
  auto mesh = std::make_shared<TriangleMesh>(compute_shape_local_mesh(model_, shape_, filtered));
  if (mesh->empty()) {
    loss(LossKind::kGeometry, fmt::format("an empty {} (nothing to draw)", geometry_type_name(shape_.geometry)));
    return;
  }
  mesh_piece(std::move(mesh), shape_key(), stem(), material_);
}

void Planner::mesh_resource(const MeshResource& res) {
  if (res.mesh < 0 || static_cast<std::size_t>(res.mesh) >= model_.meshes.size() ||
      model_.meshes[static_cast<std::size_t>(res.mesh)].parts.empty()) {
    loss(LossKind::kGeometry, fmt::format("mesh '{}', which could not be loaded; the shape is left out", res.uri));
    return;
  }
  const MeshAsset& asset = model_.meshes[static_cast<std::size_t>(res.mesh)];
  bool textured = false;
  for (const MeshPart& part : asset.parts) textured = textured || part.texture.has_value();
  if (textured) loss(LossKind::kTextures, fmt::format("the texture of mesh '{}'", res.uri), "colours are kept");
  if (sr_ && target_.references_mesh_file && target_.references_mesh_file(res)) {
    PlannedPiece piece;
    piece.kind = PlannedPiece::Kind::kMeshFile;
    piece.origin.linear() = sr_->rotation;
    piece.origin.translation() = shape_.X_LS.translation();
    piece.scale = sr_->scale * res.length_scale;
    piece.file = &res;
    piece.material = material_;
    plan_.pieces.push_back(std::move(piece));
    return;
  }
  // Converted: one mesh per part, so that each keeps its own colour.
  const std::string asset_stem =
      std::filesystem::path(asset.path).stem().string() + (asset.node.empty() ? "" : "_" + asset.node);
  for (std::size_t p = 0; p < asset.parts.size(); ++p) {
    const MeshPart& part = asset.parts[p];
    if (part.mesh.empty()) continue;
    const std::string key = fmt::format("asset:{}:{}", res.mesh, p);
    mesh_piece(borrowed(part.mesh), sr_ ? key : key + ":" + shape_key(),
               asset.parts.size() > 1 ? fmt::format("{}_{}", asset_stem, p) : asset_stem,
               material_ ? material_ : part.material);
  }
}

void Planner::mesh_piece(std::shared_ptr<const TriangleMesh> mesh, std::string key, std::string stem,
                         const std::optional<Material>& material) {
  PlannedPiece piece;
  piece.kind = PlannedPiece::Kind::kMesh;
  piece.material = material;
  piece.stem = std::move(stem);
  piece.origin.translation() = shape_.X_LS.translation();
  const bool hull_needed = target_.hull_collision && shape_.collision;
  bool spans = true;
  if (sr_) {
    // A rigid placement and a per-axis scale: the mesh file is shared, the target scales it.
    piece.origin.linear() = sr_->rotation;
    piece.scale = sr_->scale;
    if (hull_needed) {
      TriangleMesh scaled = *mesh;
      for (auto& v : scaled.vertices) v = v.cwiseProduct(piece.scale);
      spans = spans_volume(scaled);
    }
    piece.key = std::move(key);
    piece.mesh = std::move(mesh);
  } else {
    // Shear or mirror: the linear part is baked into the vertices (a mirror flips the winding).
    auto baked = std::make_shared<TriangleMesh>(*mesh);
    baked->normals.clear();  // the targets' mesh files carry face normals only
    transform_mesh(*baked, Eigen::Matrix3d(shape_.X_LS.linear()));
    if (hull_needed) spans = spans_volume(*baked);
    piece.key = key + ":baked";
    piece.mesh = std::move(baked);
  }
  if (!spans)
    piece.collision_dropped = PlannedLoss{
        LossKind::kGeometry,
        shape_.source,
        fmt::format("the collision geometry of a flat or degenerate {} ({} collides with convex hulls, which "
                    "need a volume; only its visual geom is written)",
                    geometry_type_name(shape_.geometry), target_.name),
        {}};
  plan_.pieces.push_back(std::move(piece));
}

}  // namespace

Eigen::Vector4d clamped_rgba(const Material& material) {
  return Eigen::Vector4d(material.diffuse_color.x(), material.diffuse_color.y(), material.diffuse_color.z(),
                         1.0 - material.transparency)
      .cwiseMax(0.0)
      .cwiseMin(1.0);
}

ShapePlan plan_shape(const Model& model, std::size_t link_index, std::size_t shape_index, const ShapeTarget& target,
                     DiagnosticSink& sink) {
  return Planner(model, link_index, shape_index, target, sink).plan();
}

}  // namespace bodyfmt::converters
