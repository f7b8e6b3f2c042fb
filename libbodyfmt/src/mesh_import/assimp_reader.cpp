#include "mesh_import/assimp_reader.h"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>

namespace bodyfmt::mesh {

namespace {

namespace fs = std::filesystem;

/// A file's bytes, read whole by the bounded reader, as assimp reads a file.
class BytesStream : public Assimp::IOStream {
 public:
  explicit BytesStream(FileBytes bytes) : bytes_(std::move(bytes)) {}
  size_t Read(void* buffer, size_t size, size_t count) override {
    if (size == 0) return 0;
    const size_t whole = std::min(count, (bytes_.size - position_) / size);
    std::memcpy(buffer, bytes_.data.get() + position_, whole * size);
    position_ += whole * size;
    return whole;
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? position_ : bytes_.size;
    if (offset > bytes_.size - base) return aiReturn_FAILURE;
    position_ = base + offset;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return position_; }
  size_t FileSize() const override { return bytes_.size; }
  void Flush() override {}

 private:
  FileBytes bytes_;
  size_t position_ = 0;
};

/// The files assimp opens, through the host's bounded reader (assimp's default one fopen()s
/// whatever a mesh names: a FIFO blocks it forever, /dev/zero never ends, a buffer ignores
/// --max-file-size). Only the mesh file itself and files inside its folder are opened, after
/// symbolic links are resolved; what is refused is kept in `refused` for the caller to report.
class BoundedIOSystem : public Assimp::IOSystem {
 public:
  struct Refusal {
    const char* rule;
    std::string message;
  };

  BoundedIOSystem(const AssimpHost& host, const std::string& mesh_path, std::uintmax_t max_file_bytes)
      : host_(host), mesh_path_(mesh_path), max_file_bytes_(max_file_bytes) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(fs::path(mesh_path), ec);
    folder_ = fs::weakly_canonical(absolute.parent_path(), ec);
    mesh_file_ = fs::weakly_canonical(absolute, ec);
  }

  std::vector<Refusal> refused;
  /// Textures outside the mesh's folder: not used, the mesh kept (its geometry is the model's).
  std::vector<Refusal> dropped_textures;

  /// Whether `path` is the mesh file or a file inside its folder, symbolic links resolved.
  bool inside(const std::string& path, fs::path& resolved) const {
    if (path == mesh_path_) return true;
    std::error_code ec;
    resolved = fs::weakly_canonical(fs::absolute(fs::path(path), ec), ec);
    if (!ec && resolved == mesh_file_) return true;  // the mesh file, however spelt
    const fs::path relative = ec ? fs::path("..") : resolved.lexically_relative(folder_);
    return !relative.empty() && *relative.begin() != ".." && relative.is_relative();
  }

  /// A texture the exporters and bodyview would copy: used only inside the mesh's folder; one
  /// outside is dropped with a warning, and the mesh keeps its geometry (a ROS-style DAE naming
  /// ../textures/x.png still loads, without the picture).
  bool texture_allowed(const std::string& path) {
    fs::path resolved;
    if (inside(path, resolved)) return true;
    const std::string message = "mesh file \"" + mesh_path_ + "\" names the texture \"" + path + "\"" +
                                (resolved.empty() ? std::string() : " (" + resolved.string() + ")") +
                                ", outside its folder \"" + folder_.string() + "\"; the texture is not used";
    for (const Refusal& r : dropped_textures)
      if (r.message == message) return false;
    dropped_textures.push_back({"mesh-texture-outside", message});
    return false;
  }

  /// Whether `path` may be opened: the mesh file, or a file inside its folder. Records a refusal.
  bool allowed(const std::string& path) {
    fs::path resolved;
    if (inside(path, resolved)) return true;
    if (!refused_paths_.insert(resolved.string()).second) return false;  // one finding per file
    refuse("mesh-reference-outside", "mesh file \"" + mesh_path_ + "\" names \"" + path + "\"" +
                                         (resolved.empty() ? std::string() : " (" + resolved.string() + ")") +
                                         ", outside its folder \"" + folder_.string() + "\"; the mesh is not used");
    return false;
  }

  bool Exists(const char* file) const override {
    // stat, not fopen: opening a FIFO blocks until something writes to it.
    struct stat st {};
    return ::stat(file, &st) == 0;
  }
  char getOsSeparator() const override { return '/'; }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::strchr(mode, 'w') || std::strchr(mode, 'a') || std::strchr(mode, '+')) return nullptr;
    const std::string path = file;
    if (!allowed(path)) return nullptr;
    std::string why;
    std::optional<FileBytes> bytes = host_.read_file(path, max_file_bytes_, why);
    if (!bytes) {
      // A missing file stays assimp's to judge (an OBJ without its material library loads).
      if (why != "no such file")
        refuse("mesh-file-unreadable", "cannot read \"" + path + "\", named by mesh file \"" + mesh_path_ + "\": it " +
                                           why + "; the mesh is not used");
      return nullptr;
    }
    return new BytesStream(std::move(*bytes));
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  void refuse(const char* rule, std::string message) {
    for (const Refusal& r : refused)
      if (r.message == message) return;
    refused.push_back({rule, std::move(message)});
  }

  const AssimpHost& host_;
  std::string mesh_path_;
  std::uintmax_t max_file_bytes_;
  std::set<std::string> refused_paths_;
  fs::path folder_;     // the mesh file's folder, symbolic links resolved
  fs::path mesh_file_;  // the mesh file, symbolic links resolved
};

Eigen::Affine3d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  e << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return Eigen::Affine3d(e);
}

Eigen::Vector3d to_eigen(const aiColor3D& c) { return {c.r, c.g, c.b}; }

/// Converts an assimp material the way Choreonoid's Assimp scene loader does: VRML-style
/// colours, shininess as the specular exponent, opacity as 1 - transparency.
std::optional<Material> convert_material(const aiMaterial& src) {
  aiString name;
  // assimp invents "DefaultMaterial" for formats without materials (STL); Choreonoid's own
  // STL loader has no material either, so leave it unset.
  if (src.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && std::strcmp(name.C_Str(), AI_DEFAULT_MATERIAL_NAME) == 0) {
    return std::nullopt;
  }
  Material m;
  aiColor3D color;
  if (src.Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS) m.diffuse_color = to_eigen(color);
  if (src.Get(AI_MATKEY_COLOR_SPECULAR, color) == AI_SUCCESS) m.specular_color = to_eigen(color);
  if (src.Get(AI_MATKEY_COLOR_EMISSIVE, color) == AI_SUCCESS) m.emissive_color = to_eigen(color);
  if (src.Get(AI_MATKEY_COLOR_AMBIENT, color) == AI_SUCCESS) {
    // VRML has a single ambient intensity relative to the diffuse colour.
    const Eigen::Vector3d ambient = to_eigen(color);
    const double diffuse = m.diffuse_color.maxCoeff();
    if (diffuse > 0) m.ambient_intensity = std::clamp(ambient.maxCoeff() / diffuse, 0.0, 1.0);
  }
  float value = 0;
  if (src.Get(AI_MATKEY_SHININESS, value) == AI_SUCCESS) m.specular_exponent = std::max(0.0f, value);
  if (src.Get(AI_MATKEY_OPACITY, value) == AI_SUCCESS) m.transparency = std::clamp(1.0 - value, 0.0, 1.0);
  return m;
}

std::optional<Texture> convert_texture(const AssimpHost& host, const aiMaterial& src, const std::string& path,
                                       BoundedIOSystem& files) {
  aiString uri;
  if (src.GetTextureCount(aiTextureType_DIFFUSE) == 0 || src.GetTexture(aiTextureType_DIFFUSE, 0, &uri) != AI_SUCCESS ||
      uri.length == 0) {
    return std::nullopt;
  }
  Texture texture;
  texture.uri = uri.C_Str();
  if (texture.uri.front() != '*') {  // '*n' = embedded
    texture.resolved_path = host.resolve_relative(path, texture.uri);
    // The exporters and bodyview copy the image: it must stay inside the mesh's folder too.
    if (!texture.resolved_path.empty() && !files.texture_allowed(texture.resolved_path)) return std::nullopt;
  }
  return texture;
}

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// The index of the first vertex of `src` that is not finite, or -1.
long first_non_finite_vertex(const aiMesh& src) {
  for (unsigned i = 0; i < src.mNumVertices; ++i)
    if (!finite(src.mVertices[i])) return static_cast<long>(i);
  return -1;
}

MeshPart convert_mesh(const aiMesh& src) {
  MeshPart part;
  TriangleMesh& mesh = part.mesh;
  mesh.vertices.reserve(src.mNumVertices);
  for (unsigned i = 0; i < src.mNumVertices; ++i) {
    const aiVector3D& v = src.mVertices[i];
    mesh.vertices.emplace_back(v.x, v.y, v.z);
  }
  if (src.HasNormals()) {
    for (unsigned i = 0; i < src.mNumVertices; ++i) {
      const aiVector3D& n = src.mNormals[i];
      mesh.normals.emplace_back(n.x, n.y, n.z);
    }
  }
  if (src.HasTextureCoords(0)) {
    for (unsigned i = 0; i < src.mNumVertices; ++i) {
      const aiVector3D& t = src.mTextureCoords[0][i];
      mesh.tex_coords.emplace_back(t.x, t.y);
    }
  }
  for (unsigned f = 0; f < src.mNumFaces; ++f) {
    const aiFace& face = src.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines have no surface
    mesh.triangles.push_back(
        {static_cast<int>(face.mIndices[0]), static_cast<int>(face.mIndices[1]), static_cast<int>(face.mIndices[2])});
  }
  return part;
}

/// The power of two that brings a mesh of `extent` (its bounding box's largest edge) to at
/// least kJoinExtent: aiProcess_JoinIdenticalVertices merges vertices closer than a fixed 1e-5,
/// which for a cube of 1 um edge merged corners of the same face (a sixth of its volume lost,
/// as OBJ); scaled, the merge distance is 1e-5 of kJoinExtent or less of the mesh's size, and a
/// power of two scales every float exactly (and back), so a mesh as large as kJoinExtent is
/// joined exactly as before.
constexpr double kJoinExtent = 1.0;  // m

int join_scale_exponent(const aiMesh& mesh) {
  if (mesh.mNumVertices == 0) return 0;
  aiVector3D lo = mesh.mVertices[0], hi = lo;
  for (unsigned i = 1; i < mesh.mNumVertices; ++i) {
    const aiVector3D& v = mesh.mVertices[i];
    lo = aiVector3D(std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z));
    hi = aiVector3D(std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z));
  }
  const double extent = std::max({double(hi.x) - lo.x, double(hi.y) - lo.y, double(hi.z) - lo.z});
  if (!(extent > 0) || extent >= kJoinExtent) return 0;
  // No scaled coordinate may leave float's range (3.4e38): a tiny mesh far from the origin is
  // scaled less, so it is joined as before rather than turned infinite.
  const double largest = std::max(
      {std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x), std::abs(hi.y), std::abs(hi.z), 1e-30f});
  const int wanted = static_cast<int>(std::ceil(std::log2(kJoinExtent / extent)));
  const int room = static_cast<int>(std::floor(std::log2(1e30 / largest)));
  return std::max(0, std::min(wanted, room));
}

void scale_vertices(aiMesh& mesh, int exponent) {
  if (exponent == 0) return;
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    aiVector3D& v = mesh.mVertices[i];
    v = aiVector3D(std::ldexp(v.x, exponent), std::ldexp(v.y, exponent), std::ldexp(v.z, exponent));
  }
}

/// Whether every node transform of the tree is finite (a glTF matrix or scale may not be).
bool finite_transforms(const aiNode& node) {
  const aiMatrix4x4& m = node.mTransformation;
  for (unsigned r = 0; r < 4; ++r)
    for (unsigned c = 0; c < 4; ++c)
      if (!std::isfinite(m[r][c])) return false;
  for (unsigned i = 0; i < node.mNumChildren; ++i)
    if (node.mChildren[i] && !finite_transforms(*node.mChildren[i])) return false;
  return true;
}

std::shared_ptr<SceneNode> convert_node(const aiScene& scene, const aiNode& src, const std::vector<MeshPart>& meshes) {
  auto node = std::make_shared<SceneNode>();
  node->name = src.mName.C_Str();
  node->transform = to_eigen(src.mTransformation);
  for (unsigned i = 0; i < src.mNumMeshes; ++i) {
    const unsigned index = src.mMeshes[i];
    if (index >= meshes.size()) continue;
    node->parts.push_back(meshes[index]);
  }
  for (unsigned i = 0; i < src.mNumChildren; ++i) {
    if (src.mChildren[i]) node->children.push_back(convert_node(scene, *src.mChildren[i], meshes));
  }
  return node;
}

}  // namespace

SceneTree read_with_assimp(const AssimpHost& host, const std::string& path, std::uintmax_t max_file_bytes,
                           DiagnosticSink& sink, const SourceLocation& where) {
  Assimp::Importer importer;
  auto* files = new BoundedIOSystem(host, path, max_file_bytes);
  importer.SetIOHandler(files);  // the importer owns and deletes it
  // Keep COLLADA's <unit> scale and <up_axis> conversion off: Choreonoid's Assimp loader reads
  // the raw node transforms (assimp's Y-up conversion would turn Z-up robot parts sideways).
  // Measured against UR5's reference visual_bbox (tests/unit/mesh/mesh_import_test.cpp).
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Points and lines are dropped; no ValidateDataStructure: it rejects a corpus DAE with
  // duplicate camera names (toolchain.md, assimp).
  // Vertices are joined after the read, each mesh scaled to the size the join assumes.
  const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType;
  const aiScene* scene = importer.ReadFile(path, flags);
  std::vector<int> exponents;
  if (scene && files->refused.empty()) {
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
      aiMesh& mesh = *scene->mMeshes[i];
      exponents.push_back(first_non_finite_vertex(mesh) < 0 ? join_scale_exponent(mesh) : 0);
      scale_vertices(mesh, exponents.back());
    }
    scene = importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices);
    for (unsigned i = 0; scene && i < scene->mNumMeshes && i < exponents.size(); ++i)
      scale_vertices(*scene->mMeshes[i], -exponents[i]);
  }
  const auto report_refused = [&] {
    for (const BoundedIOSystem::Refusal& r : files->refused) host.report(sink, r.rule, where, r.message);
    return !files->refused.empty();
  };
  if (report_refused()) return nullptr;
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    host.report(sink, "mesh-parse", where, "cannot read mesh file \"" + path + "\": " + importer.GetErrorString());
    return nullptr;
  }
  std::vector<MeshPart> meshes;
  meshes.reserve(scene->mNumMeshes);
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    if (const long bad = first_non_finite_vertex(*scene->mMeshes[i]); bad >= 0) {
      host.report(sink, "mesh-vertex-not-finite", where,
                  "mesh file \"" + path + "\" has a vertex that is not a finite number (mesh " + std::to_string(i) +
                      ", vertex " + std::to_string(bad) + "); the mesh is not used");
      return nullptr;
    }
    MeshPart part = convert_mesh(*scene->mMeshes[i]);
    const unsigned material = scene->mMeshes[i]->mMaterialIndex;
    if (material < scene->mNumMaterials && scene->mMaterials[material]) {
      part.material = convert_material(*scene->mMaterials[material]);
      part.texture = convert_texture(host, *scene->mMaterials[material], path, *files);
    }
    meshes.push_back(std::move(part));
  }
  if (report_refused()) return nullptr;
  for (const BoundedIOSystem::Refusal& r : files->dropped_textures) host.report(sink, r.rule, where, r.message);
  if (!finite_transforms(*scene->mRootNode)) {
    host.report(sink, "mesh-vertex-not-finite", where,
                "mesh file \"" + path + "\" has a node transform that is not finite; the mesh is not used");
    return nullptr;
  }
  return convert_node(*scene, *scene->mRootNode, meshes);
}

}  // namespace bodyfmt::mesh

extern "C" void bodyfmt_assimp_read_v3(const bodyfmt::mesh::AssimpHost* host, const char* path,
                                       std::uintmax_t max_file_bytes, bodyfmt::DiagnosticSink* sink,
                                       const bodyfmt::SourceLocation* where, bodyfmt::mesh::SceneTree* out) {
  *out = bodyfmt::mesh::read_with_assimp(*host, path, max_file_bytes, *sink, *where);
}
