#include "mesh_import/assimp_reader.h"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cstring>

namespace bodyfmt::mesh {

namespace {

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

std::optional<Texture> convert_texture(const AssimpHost& host, const aiMaterial& src, const std::string& path) {
  aiString uri;
  if (src.GetTextureCount(aiTextureType_DIFFUSE) == 0 || src.GetTexture(aiTextureType_DIFFUSE, 0, &uri) != AI_SUCCESS ||
      uri.length == 0) {
    return std::nullopt;
  }
  Texture texture;
  texture.uri = uri.C_Str();
  if (texture.uri.front() != '*') texture.resolved_path = host.resolve_relative(path, texture.uri);  // '*n' = embedded
  return texture;
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

SceneTree read_with_assimp(const AssimpHost& host, const std::string& path, DiagnosticSink& sink,
                           const SourceLocation& where) {
  Assimp::Importer importer;
  // Keep COLLADA's <unit> scale and <up_axis> conversion off: Choreonoid's Assimp loader reads
  // the raw node transforms (assimp's Y-up conversion would turn Z-up robot parts sideways).
  // Measured against UR5's reference visual_bbox (tests/unit/mesh/mesh_import_test.cpp).
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Points and lines are dropped; no ValidateDataStructure: it rejects a corpus DAE with
  // duplicate camera names (toolchain.md, assimp).
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    host.report(sink, "mesh-parse", where, "cannot read mesh file \"" + path + "\": " + importer.GetErrorString());
    return nullptr;
  }
  std::vector<MeshPart> meshes;
  meshes.reserve(scene->mNumMeshes);
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    MeshPart part = convert_mesh(*scene->mMeshes[i]);
    const unsigned material = scene->mMeshes[i]->mMaterialIndex;
    if (material < scene->mNumMaterials && scene->mMaterials[material]) {
      part.material = convert_material(*scene->mMaterials[material]);
      part.texture = convert_texture(host, *scene->mMaterials[material], path);
    }
    meshes.push_back(std::move(part));
  }
  return convert_node(*scene, *scene->mRootNode, meshes);
}

}  // namespace bodyfmt::mesh

extern "C" void bodyfmt_assimp_read_v2(const bodyfmt::mesh::AssimpHost* host, const char* path,
                                       bodyfmt::DiagnosticSink* sink, const bodyfmt::SourceLocation* where,
                                       bodyfmt::mesh::SceneTree* out) {
  *out = bodyfmt::mesh::read_with_assimp(*host, path, *sink, *where);
}
