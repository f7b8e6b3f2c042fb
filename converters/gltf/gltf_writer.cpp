#include "gltf_writer.h"

#include "gltf_finish.h"
#include "json.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/converters/loss.h>
#include <bodyfmt/converters/staged_files.h>
#include <bodyfmt/converters/transforms.h>
#include <bodyfmt/converters/value_changes.h>
#include <bodyfmt/mesh.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/tessellate.h>

#include <assimp/scene.h>
#include <assimp/version.h>
#include <fmt/format.h>
#include <assimp/Exporter.hpp>
#include <assimp/ProgressHandler.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <unordered_map>

namespace bodyfmt::gltf {
namespace {

namespace fs = std::filesystem;
constexpr std::string_view kTarget = "glTF";
/// Crease angle for tessellated primitives: smooth across the facets of a round surface
/// (18 degrees apart at the default 20 divisions, up to 51 degrees at 7), sharp at box edges
/// and cylinder caps (90 degrees), as Choreonoid shades them.
constexpr double kPrimitiveCreaseAngle = 1.0;
/// Largest texture file embedded (the loader's own file limit is larger; a texture this big
/// is almost certainly a mistake and would bloat every GLB).
constexpr std::uintmax_t kMaxTextureBytes = 64u << 20;

Json vec3(const Eigen::Vector3d& v) {
  Json a = Json::array();
  for (int i = 0; i < 3; ++i) a.push_back(v[i]);
  return a;
}

/// A limit as JSON: null where Choreonoid means unlimited (JSON has no infinity).
Json limit(double v) { return std::abs(v) >= kUnlimited ? Json() : Json(v); }

Json range(double lo, double hi) { return Json(Json::Array{limit(lo), limit(hi)}); }

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

double clamp01(double v) { return std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 0.0; }

/// Crease angle of a shape's polygon geometry, or of a mesh resource; nullopt = keep the
/// normals the mesh came with.
std::optional<double> crease_angle_of(const Geometry& g) {
  if (const auto* x = geometry_if<IndexedFaceSet>(g)) return x->crease_angle;
  if (const auto* x = geometry_if<TriangleMeshGeometry>(g)) return x->crease_angle;
  if (const auto* x = geometry_if<Extrusion>(g)) return x->crease_angle;
  if (const auto* x = geometry_if<ElevationGrid>(g)) return x->crease_angle;
  if (const auto* x = geometry_if<MeshResource>(g)) return x->crease_angle;
  return kPrimitiveCreaseAngle;
}

/// FNV-1a over the bytes of a mesh's arrays and its material.
std::uint64_t mesh_hash(const aiMesh& m) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  mix(&m.mMaterialIndex, sizeof m.mMaterialIndex);
  mix(&m.mNumVertices, sizeof m.mNumVertices);
  mix(m.mVertices, sizeof(aiVector3D) * m.mNumVertices);
  mix(m.mNormals, sizeof(aiVector3D) * m.mNumVertices);
  if (m.mTextureCoords[0]) mix(m.mTextureCoords[0], sizeof(aiVector3D) * m.mNumVertices);
  for (unsigned f = 0; f < m.mNumFaces; ++f) mix(m.mFaces[f].mIndices, sizeof(unsigned) * m.mFaces[f].mNumIndices);
  return h;
}

bool same_mesh(const aiMesh& a, const aiMesh& b) {
  const std::size_t n = a.mNumVertices;
  auto same = [n](const aiVector3D* x, const aiVector3D* y) {
    return (x == nullptr) == (y == nullptr) && (!x || std::memcmp(x, y, sizeof(aiVector3D) * n) == 0);
  };
  if (a.mMaterialIndex != b.mMaterialIndex || a.mNumVertices != b.mNumVertices || a.mNumFaces != b.mNumFaces ||
      !same(a.mVertices, b.mVertices) || !same(a.mNormals, b.mNormals) ||
      !same(a.mTextureCoords[0], b.mTextureCoords[0]))
    return false;
  for (unsigned f = 0; f < a.mNumFaces; ++f) {
    if (a.mFaces[f].mNumIndices != b.mFaces[f].mNumIndices ||
        std::memcmp(a.mFaces[f].mIndices, b.mFaces[f].mIndices, sizeof(unsigned) * a.mFaces[f].mNumIndices) != 0)
      return false;
  }
  return true;
}

/// Frees a scene's meshes once Assimp::Exporter::Export has copied the scene: Export reports
/// step 1 of 4 right after its SceneCombiner::CopyScene and reads nothing of the original
/// scene but its private data (mPrivate) afterwards (assimp 5.x).
class ReleaseAfterCopy : public Assimp::ProgressHandler {
 public:
  explicit ReleaseAfterCopy(aiScene& scene) : scene_(scene) {}
  bool Update(float) override { return true; }
  void UpdateFileWrite(int step, int steps) override {
    if (step != 1 || steps != 4 || released_) return;
    released_ = true;
    for (unsigned i = 0; i < scene_.mNumMeshes; ++i) {
      delete scene_.mMeshes[i];
      scene_.mMeshes[i] = nullptr;
    }
    scene_.mNumMeshes = 0;
  }

 private:
  aiScene& scene_;
  bool released_ = false;
};

// Passes findings on, counting them.
class CountingSink : public DiagnosticSink {
 public:
  explicit CountingSink(DiagnosticSink& inner) : inner_(inner) {}
  void report(Diagnostic d) override {
    ++count_;
    inner_.report(std::move(d));
  }
  int count() const { return count_; }

 private:
  DiagnosticSink& inner_;
  int count_ = 0;
};

class Writer {
 public:
  Writer(const Model& model, const Derived& derived, const GltfOptions& options, converters::OutputSet& output,
         DiagnosticSink& sink)
      : model_(model), derived_(derived), options_(options), output_(output), sink_(sink) {}
  ~Writer() {
    for (aiMesh* m : meshes_) delete m;  // meshes no scene owns yet (an early return)
  }

  bool run();

 private:
  struct Part {
    TriangleMesh mesh;
    std::optional<Material> material;
    std::optional<Texture> texture;
  };

  /// Adds a node under `parent` (NodeTable::kNoParent for the root) and returns its index.
  std::uint32_t node(std::uint32_t parent, NodeTable table) {
    table.parent = parent;
    tables_.nodes.push_back(std::move(table));
    return static_cast<std::uint32_t>(tables_.nodes.size() - 1);
  }
  void loss(converters::LossKind kind, const SourceLocation& at, const std::string& what,
            const std::string& hint = {}) {
    converters::report_loss(sink_, at, kTarget, kind, what, hint);
  }

  std::uint32_t write_link(std::uint32_t parent, std::size_t index);
  void write_geometry(std::uint32_t link_node, const Link& link, bool visual);
  void write_shape(std::uint32_t parent, const Link& link, std::size_t s, const Eigen::Affine3d& X, bool report);
  void write_devices(std::uint32_t link_node, std::size_t link_index);
  unsigned add_mesh(const TriangleMesh& mesh, int material, const std::string& name);
  int material_index(const Material& material, int texture);
  int texture_index(const Texture& texture, const SourceLocation& at);
  std::vector<Part> parts_of(const Shape& shape);
  static void with_normals(const Shape& shape, Part& part);
  static std::string primitive_key(const Shape& shape, TexCoords uv);

  const Model& model_;
  const Derived& derived_;
  const GltfOptions& options_;
  converters::OutputSet& output_;
  DiagnosticSink& sink_;
  std::optional<std::vector<PhysicalFinding>> joint_findings_;  // assess_joints(), on first use

  SceneTables tables_;
  std::unique_ptr<aiScene> scene_;
  std::vector<aiMesh*> meshes_;
  std::unordered_map<std::uint64_t, std::vector<unsigned>> meshes_by_hash_;
  // The mesh (with normals) of each primitive met, by primitive_key(): a generated model
  // repeats one box many times, and tessellating it and computing its normals again for each
  // was 8 % of exporting a 100,000-link chain.
  std::unordered_map<std::string, TriangleMesh> primitive_meshes_;
  std::map<std::string, int> material_keys_;
  std::map<std::string, int> texture_keys_;  ///< resolved path + wrap modes -> texture
  std::map<std::string, int> image_keys_;    ///< resolved path -> image
  std::set<std::string> image_names_;
  /// Texture files of a .gltf export, in a folder of their own so that exports never share one.
  const std::string texture_folder_ = converters::generated_folder("", "textures", output_, model_.name);
};

std::vector<Writer::Part> Writer::parts_of(const Shape& shape) {
  std::vector<Part> parts;
  const auto* resource = geometry_if<MeshResource>(shape.geometry);
  if (resource && resource->mesh >= 0 && static_cast<std::size_t>(resource->mesh) < model_.meshes.size()) {
    // Each part keeps its own material; the shape's appearance, where written, wins.
    for (const MeshPart& part : model_.meshes[static_cast<std::size_t>(resource->mesh)].parts) {
      Part p{part.mesh, part.material, part.texture};
      if (shape.appearance.material) p.material = shape.appearance.material;
      if (shape.appearance.texture) p.texture = shape.appearance.texture;
      parts.push_back(std::move(p));
    }
  } else {
    // Texture coordinates only for a textured shape: they split vertices along seams.
    const TexCoords uv = shape.appearance.texture ? TexCoords::kGenerate : TexCoords::kNone;
    const std::string key = primitive_key(shape, uv);
    if (auto known = primitive_meshes_.find(key); !key.empty() && known != primitive_meshes_.end()) {
      parts.push_back({known->second, shape.appearance.material, shape.appearance.texture});
      return parts;
    }
    GeometryAlreadyReported filtered(sink_);
    CountingSink counted(filtered);
    parts.push_back(
        {compute_shape_local_mesh(model_, shape, counted, uv), shape.appearance.material, shape.appearance.texture});
    with_normals(shape, parts.back());
    // A primitive that said something is tessellated again where it recurs, to say it there too.
    if (!key.empty() && counted.count() == 0) primitive_meshes_.emplace(key, parts.back().mesh);
    return parts;
  }
  for (Part& p : parts) with_normals(shape, p);
  return parts;
}

void Writer::with_normals(const Shape& shape, Part& part) {
  const std::optional<double> crease = crease_angle_of(shape.geometry);
  const bool has_normals = part.mesh.normals.size() == part.mesh.vertices.size() && !part.mesh.vertices.empty();
  if (crease || !has_normals) part.mesh = with_vertex_normals(part.mesh, crease.value_or(0.0));
}

std::string Writer::primitive_key(const Shape& shape, TexCoords uv) {
  // The bytes of everything the mesh of a primitive depends on; "" for other geometry.
  std::string key;
  auto add = [&key](const auto& value) { key.append(reinterpret_cast<const char*>(&value), sizeof value); };
  const Geometry& g = shape.geometry;
  if (const auto* box = geometry_if<Box>(g)) {
    add(box->size.x()), add(box->size.y()), add(box->size.z());
  } else if (const auto* sphere = geometry_if<Sphere>(g)) {
    add(sphere->radius);
  } else if (const auto* cylinder = geometry_if<Cylinder>(g)) {
    add(cylinder->radius), add(cylinder->height), add(cylinder->top), add(cylinder->bottom);
  } else if (const auto* cone = geometry_if<Cone>(g)) {
    add(cone->radius), add(cone->height), add(cone->bottom);
  } else if (const auto* capsule = geometry_if<Capsule>(g)) {
    add(capsule->radius), add(capsule->height);
  } else {
    return key;
  }
  add(g.index()), add(shape.division_number), add(uv);
  return key;
}

int Writer::texture_index(const Texture& texture, const SourceLocation& at) {
  const std::string ext = lower_extension(texture.resolved_path.empty() ? texture.uri : texture.resolved_path);
  const bool png = ext == ".png", jpeg = ext == ".jpg" || ext == ".jpeg";
  if (texture.resolved_path.empty() || !(png || jpeg)) {
    loss(converters::LossKind::kTextures, at, fmt::format("the texture '{}'", texture.uri),
         texture.resolved_path.empty() ? "the file was not found" : "glTF embeds PNG and JPEG images only");
    return -1;
  }
  const std::string key = fmt::format("{}\n{}{}", texture.resolved_path, int(texture.repeat_s), int(texture.repeat_t));
  if (auto it = texture_keys_.find(key); it != texture_keys_.end()) return it->second;

  int image = -1;
  if (auto it = image_keys_.find(texture.resolved_path); it != image_keys_.end()) {
    image = it->second;
  } else {
    std::string why;
    const std::optional<std::string> bytes = read_regular_file(texture.resolved_path, kMaxTextureBytes, why);
    if (!bytes) {
      loss(converters::LossKind::kTextures, at, fmt::format("the texture '{}'", texture.uri),
           "the file cannot be read (" + why + ")");
      return -1;
    }
    const std::string& data = *bytes;
    const bool png_magic = data.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
    const bool jpeg_magic = data.size() > 2 && data[0] == '\xFF' && data[1] == '\xD8';
    if (!png_magic && !jpeg_magic) {
      loss(converters::LossKind::kTextures, at, fmt::format("the texture '{}'", texture.uri),
           "the file is neither PNG nor JPEG data");
      return -1;
    }
    std::string name =
        fmt::format("{}{}", fs::path(texture.resolved_path).stem().string(), png_magic ? ".png" : ".jpg");
    for (int n = 2; image_names_.count(name); ++n)
      name = fmt::format("{}_{}{}", fs::path(texture.resolved_path).stem().string(), n, png_magic ? ".png" : ".jpg");
    image_names_.insert(name);
    image = static_cast<int>(tables_.images.size());
    const std::string file = texture_folder_ + "/" + name;
    tables_.images.push_back({file, png_magic ? "image/png" : "image/jpeg", data});
    if (!options_.binary) output_.add(file, data);
    image_keys_.emplace(texture.resolved_path, image);
  }
  Json sampler = Json::object();
  sampler["magFilter"] = 9729;                          // LINEAR
  sampler["minFilter"] = 9987;                          // LINEAR_MIPMAP_LINEAR
  sampler["wrapS"] = texture.repeat_s ? 10497 : 33071;  // REPEAT : CLAMP_TO_EDGE
  sampler["wrapT"] = texture.repeat_t ? 10497 : 33071;
  tables_.samplers.push_back(std::move(sampler));
  Json tex = Json::object();
  tex["sampler"] = tables_.samplers.items().size() - 1;
  tex["source"] = image;
  tables_.textures.push_back(std::move(tex));
  const int index = static_cast<int>(tables_.textures.items().size() - 1);
  texture_keys_.emplace(key, index);
  return index;
}

/// Phong (VRML97) -> PBR metallic-roughness; SUPPORT.md "Materials" gives the reasons.
int Writer::material_index(const Material& m, int texture) {
  Json pbr = Json::object();
  pbr["baseColorFactor"] = Json(Json::Array{clamp01(m.diffuse_color.x()), clamp01(m.diffuse_color.y()),
                                            clamp01(m.diffuse_color.z()), clamp01(1.0 - m.transparency)});
  pbr["metallicFactor"] = 0.0;
  const double n = std::max(0.0, m.specular_exponent);
  pbr["roughnessFactor"] = clamp01(std::pow(2.0 / (n + 2.0), 0.25));
  if (texture >= 0) pbr["baseColorTexture"]["index"] = texture;
  Json mat = Json::object();
  mat["pbrMetallicRoughness"] = std::move(pbr);
  const Eigen::Vector3d e = m.emissive_color.unaryExpr([](double v) { return clamp01(v); });
  if (!e.isZero(0)) mat["emissiveFactor"] = vec3(e);
  if (m.transparency > 0) mat["alphaMode"] = "BLEND";
  const std::string key = mat.dump();
  if (auto it = material_keys_.find(key); it != material_keys_.end()) return it->second;
  const int index = static_cast<int>(tables_.materials.size());
  Json named = Json::object();
  named["name"] = fmt::format("material{}", index);
  for (auto& [k, v] : mat.members()) named[k] = v;
  tables_.materials.push_back(std::move(named));
  material_keys_.emplace(key, index);
  return index;
}

unsigned Writer::add_mesh(const TriangleMesh& mesh, int material, const std::string& name) {
  auto* m = new aiMesh();
  m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m->mMaterialIndex = static_cast<unsigned>(material);
  m->mNumVertices = static_cast<unsigned>(mesh.vertices.size());
  m->mVertices = new aiVector3D[mesh.vertices.size()];
  m->mNormals = new aiVector3D[mesh.vertices.size()];
  const bool uv = mesh.tex_coords.size() == mesh.vertices.size();
  if (uv) {
    m->mTextureCoords[0] = new aiVector3D[mesh.vertices.size()];
    m->mNumUVComponents[0] = 2;
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices[i];
    m->mVertices[i] = aiVector3D(static_cast<ai_real>(v.x()), static_cast<ai_real>(v.y()), static_cast<ai_real>(v.z()));
    const Eigen::Vector3d nrm = i < mesh.normals.size() ? mesh.normals[i].normalized() : Eigen::Vector3d::UnitZ();
    m->mNormals[i] =
        aiVector3D(static_cast<ai_real>(nrm.x()), static_cast<ai_real>(nrm.y()), static_cast<ai_real>(nrm.z()));
    if (uv)
      m->mTextureCoords[0][i] =
          aiVector3D(static_cast<ai_real>(mesh.tex_coords[i].x()), static_cast<ai_real>(mesh.tex_coords[i].y()), 0);
  }
  m->mNumFaces = static_cast<unsigned>(mesh.triangles.size());
  m->mFaces = new aiFace[mesh.triangles.size()];
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    aiFace& face = m->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k)
      face.mIndices[k] = static_cast<unsigned>(mesh.triangles[f][static_cast<std::size_t>(k)]);
  }
  // Identical meshes are written once and shared by their nodes: glTF instancing, and assimp's
  // exporter copies its whole buffer for every mesh it appends (quadratic in the mesh count).
  const std::uint64_t key = mesh_hash(*m);
  for (unsigned index : meshes_by_hash_[key]) {
    if (same_mesh(*meshes_[index], *m)) {
      delete m;
      return index;
    }
  }
  m->mName = aiString(fmt::format("{}{}", kMarker, tables_.mesh_names.size()));
  tables_.mesh_names.push_back(name);
  meshes_.push_back(m);
  meshes_by_hash_[key].push_back(static_cast<unsigned>(meshes_.size() - 1));
  return static_cast<unsigned>(meshes_.size() - 1);
}

void Writer::write_shape(std::uint32_t parent, const Link& link, std::size_t s, const Eigen::Affine3d& X, bool report) {
  const Shape& shape = link.shapes[s];
  const std::string name = shape.name.empty() ? fmt::format("{}/shape{}", link.name, s) : shape.name.str();
  std::vector<Part> parts = parts_of(shape);
  parts.erase(std::remove_if(parts.begin(), parts.end(), [](const Part& p) { return p.mesh.empty(); }), parts.end());
  if (parts.empty()) {
    if (report)
      loss(converters::LossKind::kGeometry, shape.source,
           fmt::format("an empty {} (nothing to draw)", geometry_type_name(shape.geometry)));
    return;
  }
  NodeTable t;
  t.name = name;
  t.transform = X;
  if (!converters::decompose(X.linear())) {
    // A node must be translation, rotation and positive scale: shear and mirroring are baked
    // into the vertices (bodyfmt/mesh.h's transform_mesh: normals and winding follow).
    for (Part& part : parts) transform_mesh(part.mesh, Eigen::Matrix3d(X.linear()));
    t.transform = Eigen::Affine3d(Eigen::Translation3d(X.translation()));
  }
  const std::uint32_t shape_node = node(parent, std::move(t));
  std::vector<unsigned> mesh_indices;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    Part& part = parts[p];
    int texture = -1;
    if (part.texture) {
      if (part.mesh.tex_coords.size() == part.mesh.vertices.size()) {
        // Report once per shape (the collision copy of --both would repeat it).
        if (report)
          texture = texture_index(*part.texture, shape.source);
        else
          texture = texture_keys_.count(fmt::format("{}\n{}{}", part.texture->resolved_path,
                                                    int(part.texture->repeat_s), int(part.texture->repeat_t)))
                        ? texture_keys_[fmt::format("{}\n{}{}", part.texture->resolved_path,
                                                    int(part.texture->repeat_s), int(part.texture->repeat_t))]
                        : -1;
      } else if (report) {
        loss(converters::LossKind::kTextures, shape.source,
             fmt::format("the texture '{}' on a {}", part.texture->uri, geometry_type_name(shape.geometry)),
             geometry_is<MeshResource>(shape.geometry)
                 ? "the mesh has no texture coordinates; the colour is kept"
                 : "its texture coordinate indices point past its tex_coords; the colour is kept");
      }
    }
    const int material = material_index(part.material.value_or(Material{}), texture);
    const std::string mesh_name = parts.size() == 1 ? name : fmt::format("{}/part{}", name, p);
    mesh_indices.push_back(add_mesh(part.mesh, material, mesh_name));
  }
  // glTF allows one mesh per node: a single part goes on the shape node, several on children.
  auto attach = [this](std::uint32_t index, unsigned mesh) { tables_.nodes[index].mesh = static_cast<int>(mesh); };
  if (mesh_indices.size() == 1) {
    attach(shape_node, mesh_indices[0]);
  } else {
    for (std::size_t p = 0; p < mesh_indices.size(); ++p) {
      NodeTable pt;
      pt.name = fmt::format("{}/part{}", name, p);
      attach(node(shape_node, std::move(pt)), mesh_indices[p]);
    }
  }
}

void Writer::write_geometry(std::uint32_t link_node, const Link& link, bool visual) {
  const bool both = options_.geometry == GeometrySet::kBoth;
  std::uint32_t base = link_node;
  if (both) {
    NodeTable g;
    g.name = fmt::format("{}/{}", link.name, visual ? "visual" : "collision");
    Json extras = Json::object();
    extras["geometry"] = visual ? "visual" : "collision";
    if (!visual) extras["hidden"] = true;
    g.extras = extras.dump();
    base = node(link_node, std::move(g));
  }
  // The link's element tree: one node per frame, shapes under their innermost frame.
  std::vector<std::uint32_t> frame_nodes;
  std::vector<Eigen::Affine3d> frame_in_link;
  for (std::size_t k = 0; k < link.frames.size(); ++k) {
    const SceneFrame& f = link.frames[k];
    const bool root = f.parent < 0 || static_cast<std::size_t>(f.parent) >= k;
    NodeTable t;
    t.name = fmt::format("{}/frame{}", link.name, k);
    t.transform = f.X_PF;
    frame_nodes.push_back(node(root ? base : frame_nodes[static_cast<std::size_t>(f.parent)], std::move(t)));
    frame_in_link.push_back(root ? Eigen::Affine3d(f.X_PF)
                                 : frame_in_link[static_cast<std::size_t>(f.parent)] * f.X_PF);
  }
  for (std::size_t s = 0; s < link.shapes.size(); ++s) {
    const Shape& shape = link.shapes[s];
    if (!(visual ? shape.visual : shape.collision)) continue;
    std::uint32_t parent = base;
    Eigen::Affine3d X = shape.X_LS;
    if (shape.frame >= 0 && static_cast<std::size_t>(shape.frame) < frame_nodes.size()) {
      const Eigen::Affine3d& F = frame_in_link[static_cast<std::size_t>(shape.frame)];
      if (std::abs(F.linear().determinant()) > 1e-12) {
        parent = frame_nodes[static_cast<std::size_t>(shape.frame)];
        X = F.inverse() * shape.X_LS;
      }
    }
    const bool report = visual || !both || !shape.visual;
    write_shape(parent, link, s, X, report);
  }
}

void Writer::write_devices(std::uint32_t link_node, std::size_t link_index) {
  for (std::size_t d = 0; d < model_.devices.size(); ++d) {
    const Device& device = model_.devices[d];
    if (device.link != static_cast<LinkIndex>(link_index)) continue;
    NodeTable t;
    t.name = device.name.empty() ? fmt::format("{}/{}{}", model_.links[link_index].name, device.type, d) : device.name;
    t.transform = device.X_LD;
    Json extras = Json::object();
    extras["device_type"] = device.type;
    if (device.id >= 0) extras["device_id"] = device.id;
    if (!device.on) extras["on"] = false;
    if (const auto* cam = std::get_if<CameraParams>(&device.params)) {
      // The glTF camera looks along -Z with +Y up, as Choreonoid's "gl" optical frame.
      Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
      if (cam->optical_frame == "cv") R = Eigen::Vector3d(1, -1, -1).asDiagonal();
      if (cam->optical_frame == "robotics") R << 0, 0, -1, -1, 0, 0, 0, 1, 0;
      t.transform = device.X_LD * Eigen::Affine3d(R * cam->optical_frame_rotation);
      const double aspect = cam->height > 0 ? double(cam->width) / cam->height : 1.0;
      // Choreonoid's field of view spans the shorter image side.
      const double yfov = aspect >= 1 ? cam->field_of_view : 2 * std::atan(std::tan(cam->field_of_view / 2) / aspect);
      const bool valid = cam->width > 0 && cam->height > 0 && yfov > 0 && yfov < kPi && cam->near_clip_distance > 0 &&
                         cam->far_clip_distance > cam->near_clip_distance;
      if (!valid) {
        loss(converters::LossKind::kDevices, device.source,
             fmt::format("the camera '{}' (its size, field of view or clip distances are not a valid "
                         "glTF perspective camera)",
                         device.name),
             "the node keeps its pose");
      } else {
        if (cam->lens_type != "NORMAL")
          loss(converters::LossKind::kDevices, device.source,
               fmt::format("the {} lens of camera '{}'", cam->lens_type, device.name),
               "written as a perspective camera");
        Json c = Json::object();
        c["name"] = t.name;
        c["type"] = "perspective";
        c["perspective"]["aspectRatio"] = aspect;
        c["perspective"]["yfov"] = yfov;
        c["perspective"]["znear"] = cam->near_clip_distance;
        c["perspective"]["zfar"] = cam->far_clip_distance;
        t.camera = static_cast<int>(tables_.cameras.items().size());
        tables_.cameras.push_back(std::move(c));
        extras["resolution"] = Json(Json::Array{cam->width, cam->height});
        extras["optical_frame"] = cam->optical_frame;
      }
    } else if (const auto* light = std::get_if<LightParams>(&device.params)) {
      const bool spot = device.type == "SpotLight";
      Json l = Json::object();
      l["name"] = t.name;
      l["type"] = spot ? "spot" : "point";
      l["color"] = vec3(light->color.unaryExpr([](double v) { return clamp01(v); }));
      // KHR's intensity is in candela; Choreonoid's is a unitless factor (0..1 in practice).
      // It is written as is, 1 cd per unit (SUPPORT.md "Cameras and lights"). A light that is
      // off shines with 0, as in Choreonoid, and keeps its factor in extras.
      const double intensity = std::isfinite(light->intensity) ? std::max(0.0, light->intensity) : 0.0;
      l["intensity"] = device.on ? intensity : 0.0;
      if (!device.on) extras["intensity"] = intensity;
      if (spot) {
        // A KHR light shines along its node's -Z: turn -Z onto `direction`.
        const Eigen::Vector3d dir = light->direction.normalized();
        if (dir.allFinite()) {
          const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(-Eigen::Vector3d::UnitZ(), dir);
          t.transform = device.X_LD * Eigen::Affine3d(q.toRotationMatrix());
        }
        const double outer = std::clamp(light->cut_off_angle, 1e-6, kPi / 2);
        const double inner = std::clamp(light->beam_width, 0.0, outer - 1e-6);
        l["spot"]["innerConeAngle"] = inner;
        l["spot"]["outerConeAngle"] = outer;
        if (light->cut_off_exponent != 0 && light->beam_width < light->cut_off_angle)
          extras["cut_off_exponent"] = light->cut_off_exponent;
      }
      loss(converters::LossKind::kDevices, device.source,
           fmt::format("the attenuation [{}, {}, {}] of light '{}'", light->attenuation.x(), light->attenuation.y(),
                       light->attenuation.z(), device.name),
           "KHR_lights_punctual lights fall off with the inverse square of the distance");
      extras["attenuation"] = vec3(light->attenuation);
      t.light = static_cast<int>(tables_.lights.items().size());
      tables_.lights.push_back(std::move(l));
    } else {
      loss(converters::LossKind::kDevices, device.source, fmt::format("the {} device '{}'", device.type, device.name),
           "an empty node keeps its name and pose; extras give its type");
    }
    t.extras = extras.dump();
    node(link_node, std::move(t));
  }
}

std::uint32_t Writer::write_link(std::uint32_t parent, std::size_t index) {
  const Link& link = model_.links[index];
  NodeTable t;
  t.name = link.name;
  t.transform = link.X_PL;
  Json x = Json::object();
  x["joint_name"] = link.joint_name.empty() ? link.name : link.joint_name.str();
  x["joint_type"] = std::string(joint_type_name(link.joint_type));
  const bool moving = link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic ||
                      link.joint_type == JointType::kPseudoContinuousTrack;
  if (moving) {
    const Eigen::Vector3d axis = link.joint_axis.normalized();
    x["joint_axis"] = vec3(axis.allFinite() ? axis : link.joint_axis);
    // A viewer turns the joint about a direction; an axis the gate finds not of unit length is
    // then a changed value, said at it as body2urdf and body2mjcf say it.
    if (!joint_findings_) joint_findings_ = assess_joints(model_);
    if (const auto change = converters::axis_change(model_, *joint_findings_, index, "a glTF viewer"))
      report_rule(sink_, "export-value-changed", change->at, change->what + " (extras.joint_axis)");
  }
  if (link.joint_id >= 0) x["joint_id"] = link.joint_id;
  if (link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic) {
    x["joint_range"] = range(link.joint_range_lower, link.joint_range_upper);
    x["joint_velocity_range"] = range(link.velocity_lower, link.velocity_upper);
  }
  if (std::abs(link.effort_lower) < kUnlimited || std::abs(link.effort_upper) < kUnlimited)
    x["joint_effort_range"] = range(link.effort_lower, link.effort_upper);
  if (link.initial_displacement != 0) x["initial_joint_displacement"] = link.initial_displacement;
  if (link.joint_axis_inertia != 0) x["joint_axis_inertia"] = link.joint_axis_inertia;
  if (!link.actuation_mode.empty()) x["actuation_mode"] = link.actuation_mode.str();
  if (!link.contact_material.empty()) x["contact_material"] = link.contact_material.str();
  // Mass data, so that nothing of the link is silently dropped (glTF has no physics).
  const MassProperties& mp = derived_.mass[index];
  x["mass"] = mp.mass;
  x["center_of_mass"] = vec3(mp.center_of_mass);
  Json inertia = Json::array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) inertia.push_back(mp.inertia(r, c));
  x["inertia"] = std::move(inertia);
  if (link.joint_type == JointType::kPseudoContinuousTrack) {
    loss(converters::LossKind::kTracks, source_of(link, LinkSources::kJointType),
         fmt::format("the belt motion of the continuous track '{}'", link.name),
         "the link and its shapes are kept; extras.joint_type says it is a track");
  }
  t.extras = x.dump();
  const std::uint32_t n = node(parent, std::move(t));
  if (options_.geometry != GeometrySet::kCollision) write_geometry(n, link, true);
  if (options_.geometry != GeometrySet::kVisual) write_geometry(n, link, false);
  write_devices(n, index);
  return n;
}

bool Writer::run() {
  tables_.generator = fmt::format("bodyfmt {} body2gltf (assimp {}.{}.{} glTF2 exporter, post-processed)",
                                  options_.version, aiGetVersionMajor(), aiGetVersionMinor(), aiGetVersionRevision());
  // Body is Z-up, glTF Y-up: the model node turns +Z to +Y (and +Y to -Z).
  NodeTable top;
  top.name = model_.name.empty() ? "body" : model_.name;
  top.transform.linear() << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  Json extras = Json::object();
  extras["up_axis_converted_from"] = "Z";
  top.extras = extras.dump();
  // Room for the usual nodes (link, frames, shapes, devices; a mesh part adds one more).
  std::size_t expected = 1 + model_.devices.size();
  const std::size_t groups = options_.geometry == GeometrySet::kBoth ? 2 : 1;
  for (const Link& link : model_.links) expected += 1 + groups * (1 + link.frames.size() + link.shapes.size());
  tables_.nodes.reserve(expected);
  const std::uint32_t root = node(NodeTable::kNoParent, std::move(top));
  // Links are in depth-first pre-order, parents first: one pass, no recursion per tree level.
  std::vector<std::uint32_t> link_nodes(model_.links.size(), NodeTable::kNoParent);
  for (std::size_t i = 0; i < model_.links.size(); ++i) {
    const LinkIndex parent = model_.links[i].parent;
    link_nodes[i] = write_link(parent >= 0 ? link_nodes[static_cast<std::size_t>(parent)] : root, i);
  }

  for (const ExtraJoint& ej : model_.extra_joints) {
    const std::string l1 = ej.link1 >= 0 ? model_.links[static_cast<std::size_t>(ej.link1)].name : "?";
    const std::string l2 = ej.link2 >= 0 ? model_.links[static_cast<std::size_t>(ej.link2)].name : "?";
    loss(converters::LossKind::kExtraJoints, ej.source,
         fmt::format("the {} extra joint between '{}' and '{}' (a closed loop)", ej.type, l1, l2));
  }

  // assimp gets the meshes and materials, and one empty root node (a scene needs one): the
  // node hierarchy is written by finish_gltf from the tables. An aiNode costs over 1 KB (a
  // fixed-size name) and assimp copies and converts each, about 3 KB per glTF node in all.
  scene_ = std::make_unique<aiScene>();
  scene_->mRootNode = new aiNode(fmt::format("{}0", kMarker));
  const std::size_t nmat = std::max<std::size_t>(1, tables_.materials.size());
  scene_->mNumMaterials = static_cast<unsigned>(nmat);
  scene_->mMaterials = new aiMaterial*[nmat];
  for (std::size_t i = 0; i < nmat; ++i) {
    scene_->mMaterials[i] = new aiMaterial();
    const aiString name(fmt::format("{}{}", kMarker, i));
    scene_->mMaterials[i]->AddProperty(&name, AI_MATKEY_NAME);
  }
  scene_->mNumMeshes = static_cast<unsigned>(meshes_.size());
  scene_->mMeshes = new aiMesh*[std::max<std::size_t>(1, meshes_.size())];
  std::copy(meshes_.begin(), meshes_.end(), scene_->mMeshes);
  meshes_.clear();

  std::string error;
  std::optional<FinishedGltf> done;
  const std::string stem = output_.main_path().stem().string();
  const std::string bin_name = (stem.empty() ? std::string("model") : stem) + ".bin";
  {
    Assimp::Exporter exporter;
    // Our meshes are freed as soon as assimp has its own copy of the scene; the aiScene itself
    // stays, as Export still reads its private data.
    auto* release = new ReleaseAfterCopy(*scene_);
    exporter.SetProgressHandler(release);
    const aiExportDataBlob* blob = exporter.ExportToBlob(scene_.get(), "glb2");
    exporter.SetProgressHandler(nullptr);  // hands the handler back (the exporter does not delete it)
    delete release;
    scene_.reset();
    if (!blob) {
      error = exporter.GetErrorString();
    } else {
      done = finish_gltf(std::string_view(static_cast<const char*>(blob->data), blob->size), tables_,
                         options_.binary ? std::string() : bin_name, &error);
    }
  }
  if (!done) {
    report_rule(sink_, "export-write", model_.source, "assimp's glTF2 export failed: " + error);
    output_.fail();
    return false;
  }
  if (options_.binary) {
    output_.set_main(pack_glb(done->json, done->bin));
  } else {
    done->json += '\n';
    output_.set_main(std::move(done->json));
    if (!done->bin.empty()) output_.add(bin_name, std::move(done->bin));
  }
  return true;
}

}  // namespace

bool write_gltf(const Model& model, const Derived& derived, const GltfOptions& options, converters::OutputSet& output,
                DiagnosticSink& sink) {
  // No step recurses per tree level (assimp sees one node; the hierarchy is written from the
  // tables with an explicit stack), so a 1,000,000-link chain needs no special stack.
  Writer writer(model, derived, options, output, sink);
  return writer.run();
}

}  // namespace bodyfmt::gltf
