#include "gltf_finish.h"

#include <bodyfmt/converters/transforms.h>

#include <charconv>
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
  int index = -1;
  const char* digits = s.data() + kMarker.size();
  if (std::from_chars(digits, s.data() + s.size(), index).ec != std::errc()) return -1;
  return index;
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

/// The node hierarchy from the tables, as assimp's exporter would write an aiNode tree of the
/// same shape (depth-first pre-order from node 0, children in creation order, name, children,
/// mesh), completed with the double-precision transform, camera, light and extras. Each node
/// is built and written on its own, so no tree of the whole array is held.
std::string node_array(const SceneTables& tables, const std::vector<int>& mesh_out, bool& lights_used) {
  const std::size_t n = tables.nodes.size();
  // Children of node i: kids[first[i] .. first[i + 1]).
  std::vector<std::uint32_t> first(n + 1, 0), kids;
  for (std::size_t i = 1; i < n; ++i)
    if (tables.nodes[i].parent < i) ++first[tables.nodes[i].parent + 1];
  for (std::size_t i = 0; i < n; ++i) first[i + 1] += first[i];
  kids.resize(first[n]);
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t i = 1; i < n; ++i)
    if (tables.nodes[i].parent < i) kids[fill[tables.nodes[i].parent]++] = static_cast<std::uint32_t>(i);
  fill = {};
  // glTF index of each node: depth-first pre-order (an explicit stack: chains are deep).
  std::vector<std::uint32_t> order, out_index(n, NodeTable::kNoParent), stack;
  order.reserve(n);
  if (n) stack.push_back(0);
  while (!stack.empty()) {
    const std::uint32_t v = stack.back();
    stack.pop_back();
    out_index[v] = static_cast<std::uint32_t>(order.size());
    order.push_back(v);
    for (std::uint32_t k = first[v + 1]; k > first[v]; --k) stack.push_back(kids[k - 1]);
  }
  std::string text = "[";
  for (const std::uint32_t v : order) {
    const NodeTable& t = tables.nodes[v];
    Json node = Json::object();
    node["name"] = t.name;
    if (first[v + 1] > first[v]) {
      Json children = Json::array();
      children.items().reserve(first[v + 1] - first[v]);
      for (std::uint32_t k = first[v]; k < first[v + 1]; ++k)
        children.push_back(static_cast<std::size_t>(out_index[kids[k]]));
      node["children"] = std::move(children);
    }
    if (t.mesh >= 0 && static_cast<std::size_t>(t.mesh) < mesh_out.size() &&
        mesh_out[static_cast<std::size_t>(t.mesh)] >= 0)
      node["mesh"] = mesh_out[static_cast<std::size_t>(t.mesh)];
    set_transform(node, t.transform);
    if (t.camera >= 0) node["camera"] = t.camera;
    if (t.light >= 0) {
      node["extensions"]["KHR_lights_punctual"]["light"] = t.light;
      lights_used = true;
    }
    if (!t.extras.empty()) node["extras"] = Json::raw(t.extras);
    if (text.size() > 1) text += ',';
    node.dump_to(text);
  }
  text += ']';
  return text;
}

struct GlbChunks {
  std::string_view json, bin;
};

/// The JSON and binary chunks of a GLB file, as views into it.
std::optional<GlbChunks> glb_chunks(std::string_view glb) {
  if (glb.size() < 20 || glb.substr(0, 4) != "glTF" || read_u32(glb, 4) != 2) return std::nullopt;
  GlbChunks out;
  std::size_t at = 12;
  while (at + 8 <= glb.size()) {
    const std::uint32_t len = read_u32(glb, at), type = read_u32(glb, at + 4);
    if (at + 8 + len > glb.size()) return std::nullopt;
    if (type == 0x4E4F534A) out.json = glb.substr(at + 8, len);
    if (type == 0x004E4942) out.bin = glb.substr(at + 8, len);
    at += 8 + len;
  }
  if (out.json.empty()) return std::nullopt;
  return out;
}

}  // namespace

std::optional<FinishedGltf> unpack_glb(std::string_view glb) {
  const std::optional<GlbChunks> chunks = glb_chunks(glb);
  if (!chunks) return std::nullopt;
  return FinishedGltf{std::string(chunks->json), std::string(chunks->bin)};
}

std::string pack_glb(const std::string& json, const std::string& bin) {
  const std::size_t json_padded = (json.size() + 3) / 4 * 4, bin_padded = (bin.size() + 3) / 4 * 4;
  std::string out;
  out.reserve(12 + 8 + json_padded + (bin.empty() ? 0 : 8 + bin_padded));
  out = "glTF";
  append_u32(out, 2);
  append_u32(out, static_cast<std::uint32_t>(12 + 8 + json_padded + (bin.empty() ? 0 : 8 + bin_padded)));
  append_u32(out, static_cast<std::uint32_t>(json_padded));
  append_u32(out, 0x4E4F534A);
  out += json;
  out.append(json_padded - json.size(), ' ');
  if (!bin.empty()) {
    append_u32(out, static_cast<std::uint32_t>(bin_padded));
    append_u32(out, 0x004E4942);
    out += bin;
    out.append(bin_padded - bin.size(), '\0');
  }
  return out;
}

std::optional<FinishedGltf> finish_gltf(std::string_view glb, const SceneTables& tables, const std::string& bin_uri,
                                        std::string* error) {
  const std::optional<GlbChunks> parts = glb_chunks(glb);
  if (!parts) {
    if (error) *error = "assimp did not write a GLB container";
    return std::nullopt;
  }
  auto parsed = Json::parse(parts->json, error);
  if (!parsed) return std::nullopt;
  Json& doc = *parsed;
  std::string bin(parts->bin);

  // Materials: the writer's own, only those a primitive uses, in first-use order.
  std::vector<int> assimp_to_ours;
  if (const Json* mats = doc.find("materials"))
    for (const Json& m : mats->items()) assimp_to_ours.push_back(marker_index(m.find("name")));
  std::map<int, int> ours_to_out;
  Json materials = Json::array();
  std::vector<int> mesh_out(tables.mesh_names.size(), -1);  // the writer's mesh -> assimp's index
  if (Json* meshes = doc.find("meshes")) {
    for (std::size_t out = 0; out < meshes->items().size(); ++out) {
      Json& mesh = meshes->items()[out];
      const int mi = marker_index(mesh.find("name"));
      if (mi >= 0 && static_cast<std::size_t>(mi) < tables.mesh_names.size()) {
        mesh["name"] = tables.mesh_names[static_cast<std::size_t>(mi)];
        mesh_out[static_cast<std::size_t>(mi)] = static_cast<int>(out);
      }
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
  bool lights_used = false;
  doc["nodes"] = Json::raw(node_array(tables, mesh_out, lights_used));
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
