#include "gltf_finish.h"

#include <bodyfmt/converters/transforms.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>

namespace bodyfmt::gltf {
namespace {

std::uint32_t read_u32(std::string_view s, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, s.data() + at, 4);  // GLB is little-endian, as every supported host
  return v;
}

void append_u32(std::string& s, std::uint32_t v) {
  char b[4];
  std::memcpy(b, &v, 4);
  s.append(b, 4);
}

/// The marker index in an assimp-written name, or -1.
int marker_index(const Json* name) {
  if (!name || !name->is_string()) return -1;
  const std::string& s = name->string();
  if (s.compare(0, kMarker.size(), kMarker) != 0) return -1;
  try {
    return std::stoi(s.substr(kMarker.size()));
  } catch (...) {
    return -1;
  }
}

Json vec(std::initializer_list<double> v) {
  Json a = Json::array();
  for (double x : v) a.push_back(x);
  return a;
}

/// TRS when the linear part is a rotation times a positive scale, else the column-major matrix.
void set_transform(Json& node, const Eigen::Affine3d& X) {
  for (const char* k : {"matrix", "translation", "rotation", "scale"}) node.erase(k);
  const Eigen::Vector3d t = X.translation();
  const auto sr = converters::decompose(X.linear());
  if (!sr) {
    Json m = Json::array();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m.push_back(X.matrix()(r, c));
    node["matrix"] = std::move(m);
    return;
  }
  if (!t.isZero(0)) node["translation"] = vec({t.x(), t.y(), t.z()});
  Eigen::Quaterniond q(sr->rotation);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;  // one of the two equal quaternions, always the same one
  if (!(q.x() == 0 && q.y() == 0 && q.z() == 0)) node["rotation"] = vec({q.x(), q.y(), q.z(), q.w()});
  if (!(sr->scale.array() == 1).all()) node["scale"] = vec({sr->scale.x(), sr->scale.y(), sr->scale.z()});
}

void normalise_normals(Json& doc, std::string& bin) {
  Json* accessors = doc.find("accessors");
  Json* views = doc.find("bufferViews");
  Json* meshes = doc.find("meshes");
  if (!accessors || !views || !meshes) return;
  std::set<int> normal_accessors;
  for (Json& mesh : meshes->items())
    if (Json* prims = mesh.find("primitives"))
      for (Json& p : prims->items())
        if (Json* attrs = p.find("attributes"))
          if (Json* n = attrs->find("NORMAL")) normal_accessors.insert(n->integer());
  for (int a : normal_accessors) {
    if (a < 0 || static_cast<std::size_t>(a) >= accessors->items().size()) continue;
    Json& acc = accessors->items()[static_cast<std::size_t>(a)];
    const Json* bv = acc.find("bufferView");
    if (!bv || acc["componentType"].integer() != 5126 || acc["type"].string() != "VEC3") continue;
    Json& view = views->items()[static_cast<std::size_t>(bv->integer())];
    const std::size_t stride = view.find("byteStride") ? static_cast<std::size_t>(view["byteStride"].integer()) : 12;
    const std::size_t base = static_cast<std::size_t>((view.find("byteOffset") ? view["byteOffset"].number() : 0) +
                                                      (acc.find("byteOffset") ? acc["byteOffset"].number() : 0));
    const std::size_t count = static_cast<std::size_t>(acc["count"].number());
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t at = base + i * stride;
      if (at + 12 > bin.size()) break;
      float v[3];
      std::memcpy(v, bin.data() + at, 12);
      const double len = std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
      if (len > 0 && std::isfinite(len)) {
        for (float& x : v) x = static_cast<float>(x / len);
      } else {
        v[0] = 0, v[1] = 0, v[2] = 1;  // a degenerate corner: any unit vector is as good
      }
      std::memcpy(bin.data() + at, v, 12);
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
    }
    if (acc.find("min") && count) acc["min"] = vec({lo[0], lo[1], lo[2]});
    if (acc.find("max") && count) acc["max"] = vec({hi[0], hi[1], hi[2]});
  }
}

}  // namespace

std::optional<FinishedGltf> unpack_glb(std::string_view glb) {
  if (glb.size() < 20 || glb.substr(0, 4) != "glTF" || read_u32(glb, 4) != 2) return std::nullopt;
  FinishedGltf out;
  std::size_t at = 12;
  while (at + 8 <= glb.size()) {
    const std::uint32_t len = read_u32(glb, at), type = read_u32(glb, at + 4);
    if (at + 8 + len > glb.size()) return std::nullopt;
    if (type == 0x4E4F534A) out.json.assign(glb.substr(at + 8, len));
    if (type == 0x004E4942) out.bin.assign(glb.substr(at + 8, len));
    at += 8 + len;
  }
  if (out.json.empty()) return std::nullopt;
  return out;
}

std::string pack_glb(const std::string& json, const std::string& bin) {
  std::string j = json, b = bin;
  while (j.size() % 4) j += ' ';
  while (b.size() % 4) b += '\0';
  std::string out = "glTF";
  append_u32(out, 2);
  append_u32(out, static_cast<std::uint32_t>(12 + 8 + j.size() + (b.empty() ? 0 : 8 + b.size())));
  append_u32(out, static_cast<std::uint32_t>(j.size()));
  append_u32(out, 0x4E4F534A);
  out += j;
  if (!b.empty()) {
    append_u32(out, static_cast<std::uint32_t>(b.size()));
    append_u32(out, 0x004E4942);
    out += b;
  }
  return out;
}

std::optional<FinishedGltf> finish_gltf(std::string_view glb, const SceneTables& tables, const std::string& bin_uri,
                                        std::string* error) {
  auto parts = unpack_glb(glb);
  if (!parts) {
    if (error) *error = "assimp did not write a GLB container";
    return std::nullopt;
  }
  auto parsed = Json::parse(parts->json, error);
  if (!parsed) return std::nullopt;
  Json& doc = *parsed;
  std::string bin = std::move(parts->bin);

  // Nodes: real names, double-precision transforms, extras, cameras and lights.
  bool lights_used = false;
  if (Json* nodes = doc.find("nodes")) {
    for (Json& node : nodes->items()) {
      const int i = marker_index(node.find("name"));
      if (i < 0 || static_cast<std::size_t>(i) >= tables.nodes.size()) continue;
      const NodeTable& t = tables.nodes[static_cast<std::size_t>(i)];
      node["name"] = t.name;
      set_transform(node, t.transform);
      if (t.camera >= 0) node["camera"] = t.camera;
      if (t.light >= 0) {
        node["extensions"]["KHR_lights_punctual"]["light"] = t.light;
        lights_used = true;
      }
      node.erase("extras");
      if (!t.extras.is_null()) node["extras"] = t.extras;
    }
  }

  // Materials: the writer's own, only those a primitive uses, in first-use order.
  std::vector<int> assimp_to_ours;
  if (const Json* mats = doc.find("materials"))
    for (const Json& m : mats->items()) assimp_to_ours.push_back(marker_index(m.find("name")));
  std::map<int, int> ours_to_out;
  Json materials = Json::array();
  if (Json* meshes = doc.find("meshes")) {
    for (Json& mesh : meshes->items()) {
      const int mi = marker_index(mesh.find("name"));
      if (mi >= 0 && static_cast<std::size_t>(mi) < tables.mesh_names.size())
        mesh["name"] = tables.mesh_names[static_cast<std::size_t>(mi)];
      if (Json* prims = mesh.find("primitives")) {
        for (Json& p : prims->items()) {
          Json* m = p.find("material");
          if (!m) continue;
          const int a = m->integer();
          const int ours = a >= 0 && static_cast<std::size_t>(a) < assimp_to_ours.size()
                               ? assimp_to_ours[static_cast<std::size_t>(a)]
                               : -1;
          if (ours < 0 || static_cast<std::size_t>(ours) >= tables.materials.size()) {
            p.erase("material");
            continue;
          }
          auto [it, added] = ours_to_out.emplace(ours, static_cast<int>(materials.items().size()));
          if (added) materials.push_back(tables.materials[static_cast<std::size_t>(ours)]);
          *m = it->second;
        }
      }
    }
  }
  doc.erase("materials");
  for (const char* k : {"textures", "images", "samplers"}) doc.erase(k);
  if (!materials.items().empty()) doc["materials"] = std::move(materials);

  normalise_normals(doc, bin);

  // Images: in the binary buffer (GLB) or beside the .gltf file.
  if (!tables.images.empty()) {
    Json images = Json::array();
    for (const ImageTable& image : tables.images) {
      Json im = Json::object();
      if (bin_uri.empty()) {
        while (bin.size() % 4) bin += '\0';
        Json view = Json::object();
        view["buffer"] = 0;
        if (!bin.empty()) view["byteOffset"] = bin.size();
        view["byteLength"] = image.bytes.size();
        bin += image.bytes;
        doc["bufferViews"].push_back(std::move(view));
        im["bufferView"] = doc["bufferViews"].items().size() - 1;
        im["mimeType"] = image.mime_type;
      } else {
        im["uri"] = image.file_name;
      }
      images.push_back(std::move(im));
    }
    doc["samplers"] = tables.samplers;
    doc["images"] = std::move(images);
    doc["textures"] = tables.textures;
  }

  if (!tables.cameras.items().empty()) doc["cameras"] = tables.cameras;
  doc.erase("extensionsUsed");
  doc.erase("extensionsRequired");
  doc.erase("extensions");
  if (lights_used) {
    doc["extensions"]["KHR_lights_punctual"]["lights"] = tables.lights;
    doc["extensionsUsed"] = Json(Json::Array{Json("KHR_lights_punctual")});
  }

  // The buffer: assimp's, grown by the images; none at all when empty.
  if (bin.empty()) {
    doc.erase("buffers");
  } else {
    Json buffer = Json::object();
    if (!bin_uri.empty()) buffer["uri"] = bin_uri;
    buffer["byteLength"] = bin.size();
    doc["buffers"] = Json(Json::Array{std::move(buffer)});
  }

  Json& asset = doc["asset"];
  asset["generator"] = tables.generator;
  asset["version"] = "2.0";

  // asset first, as people reading the file expect it.
  Json ordered = Json::object();
  ordered["asset"] = asset;
  for (auto& [k, v] : doc.members())
    if (k != "asset") ordered[k] = std::move(v);
  return FinishedGltf{ordered.dump(), std::move(bin)};
}

}  // namespace bodyfmt::gltf
