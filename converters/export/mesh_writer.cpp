#include <bodyfmt/converters/mesh_writer.h>

#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>

#include <cstdint>
#include <cstring>
#include <regex>

namespace bodyfmt::converters {

std::string_view mesh_format_extension(MeshFormat format) { return format == MeshFormat::kStl ? "stl" : "dae"; }

namespace {

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
}

void put_float(std::string& out, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  put_u32(out, bits);  // little-endian regardless of the host
}

}  // namespace

std::string write_stl(const TriangleMesh& mesh) {
  std::string out;
  // The header must not start with "solid", which readers take for ASCII STL.
  std::string header = "binary STL written by bodyfmt";
  header.resize(80, ' ');
  out += header;
  put_u32(out, static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d* corners[] = {&n, &a, &b, &c};
    for (const Eigen::Vector3d* v : corners) {
      put_float(out, v->x());
      put_float(out, v->y());
      put_float(out, v->z());
    }
    out += '\0';
    out += '\0';
  }
  return out;
}

std::optional<std::string> write_dae(const TriangleMesh& mesh, const std::optional<Material>& material,
                                     std::string_view name, std::string& error) {
  // The aiScene destructor frees these arrays, so they are allocated with new[].
  aiScene scene;
  scene.mRootNode = new aiNode();
  scene.mRootNode->mName = aiString(std::string(name));
  scene.mNumMaterials = 1;
  scene.mMaterials = new aiMaterial*[1];
  scene.mMaterials[0] = new aiMaterial();
  {
    aiMaterial* m = scene.mMaterials[0];
    const aiString material_name(std::string(name) + "_material");
    m->AddProperty(&material_name, AI_MATKEY_NAME);
    const Material mat = material.value_or(Material{});
    const aiColor4D diffuse(static_cast<ai_real>(mat.diffuse_color.x()), static_cast<ai_real>(mat.diffuse_color.y()),
                            static_cast<ai_real>(mat.diffuse_color.z()), static_cast<ai_real>(1.0 - mat.transparency));
    m->AddProperty(&diffuse, 1, AI_MATKEY_COLOR_DIFFUSE);
    const aiColor4D emissive(static_cast<ai_real>(mat.emissive_color.x()), static_cast<ai_real>(mat.emissive_color.y()),
                             static_cast<ai_real>(mat.emissive_color.z()), 1);
    m->AddProperty(&emissive, 1, AI_MATKEY_COLOR_EMISSIVE);
    const aiColor4D specular(static_cast<ai_real>(mat.specular_color.x()), static_cast<ai_real>(mat.specular_color.y()),
                             static_cast<ai_real>(mat.specular_color.z()), 1);
    m->AddProperty(&specular, 1, AI_MATKEY_COLOR_SPECULAR);
    const float opacity = static_cast<float>(1.0 - mat.transparency);
    m->AddProperty(&opacity, 1, AI_MATKEY_OPACITY);
  }
  scene.mNumMeshes = 1;
  scene.mMeshes = new aiMesh*[1];
  aiMesh* m = scene.mMeshes[0] = new aiMesh();
  m->mName = aiString(std::string(name));
  m->mMaterialIndex = 0;
  m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m->mNumVertices = static_cast<unsigned>(mesh.vertices.size());
  m->mVertices = new aiVector3D[mesh.vertices.size()];
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto& v = mesh.vertices[i];
    m->mVertices[i] = aiVector3D(static_cast<ai_real>(v.x()), static_cast<ai_real>(v.y()), static_cast<ai_real>(v.z()));
  }
  if (mesh.normals.size() == mesh.vertices.size() && !mesh.normals.empty()) {
    m->mNormals = new aiVector3D[mesh.normals.size()];
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
      const auto& n = mesh.normals[i];
      m->mNormals[i] =
          aiVector3D(static_cast<ai_real>(n.x()), static_cast<ai_real>(n.y()), static_cast<ai_real>(n.z()));
    }
  }
  m->mNumFaces = static_cast<unsigned>(mesh.triangles.size());
  m->mFaces = new aiFace[mesh.triangles.size()];
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    aiFace& f = m->mFaces[i];
    f.mNumIndices = 3;
    f.mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) f.mIndices[k] = static_cast<unsigned>(mesh.triangles[i][static_cast<std::size_t>(k)]);
  }
  scene.mRootNode->mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};

  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(&scene, "collada");
  if (!blob) {
    error = exporter.GetErrorString();
    return std::nullopt;
  }
  std::string text(static_cast<const char*>(blob->data), blob->size);
  // assimp stamps the export time; a fixed date keeps the output byte-identical.
  static const std::regex created("<created>[^<]*</created>");
  static const std::regex modified("<modified>[^<]*</modified>");
  text = std::regex_replace(text, created, "<created>2000-01-01T00:00:00</created>");
  text = std::regex_replace(text, modified, "<modified>2000-01-01T00:00:00</modified>");
  return text;
}

std::optional<std::string> write_mesh(MeshFormat format, const TriangleMesh& mesh,
                                      const std::optional<Material>& material, std::string_view name,
                                      std::string& error) {
  if (format == MeshFormat::kStl) return write_stl(mesh);
  return write_dae(mesh, material, name, error);
}

}  // namespace bodyfmt::converters
