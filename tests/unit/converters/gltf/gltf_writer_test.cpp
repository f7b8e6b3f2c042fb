// body2gltf's writer: a round trip through assimp's glTF importer on every corpus model,
// losses at their source lines, determinism, cameras, lights, textures and the JSON model.
#include "gltf_writer.h"
#include "gltf_finish.h"
#include "json.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>
#include <bodyfmt/mesh.h>

#include <assimp/scene.h>
#include <doctest/doctest.h>
#include <fmt/format.h>
#include <assimp/Importer.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace bodyfmt::gltf {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(BODYFMT_TEST_DATA_DIR) / "gltf";
const fs::path kCorpus = fs::path(BODYFMT_SHARED_DIR) / "corpus";

struct Export {
  std::optional<Model> model;
  Derived derived;
  CollectingSink sink;
  std::map<std::string, std::string> files;
  std::string main;
};

std::unique_ptr<Export> export_model(const fs::path& path, GltfOptions options = {}, const std::string& out = "m.glb") {
  auto e = std::make_unique<Export>();
  e->model = load_body(path.string(), LoadOptions{}, e->sink);
  REQUIRE_MESSAGE(e->model, path.string());
  e->derived = compute_derived(*e->model, e->sink);
  options.binary = fs::path(out).extension() == ".glb";
  converters::OutputSet set(fs::temp_directory_path() / "bodyfmt_gltf_test" / out);
  REQUIRE(write_gltf(*e->model, e->derived, options, set, e->sink));
  e->files = set.files();
  e->main = e->files.at(out);
  return e;
}

Json json_of(const std::string& main) {
  auto glb = unpack_glb(main);
  std::string error;
  auto doc = Json::parse(glb ? glb->json : main, &error);
  REQUIRE_MESSAGE(doc, error);
  return *doc;
}

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d r;
  r << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return r;
}

Eigen::Matrix4d z_up_to_y_up() {
  Eigen::Matrix4d R = Eigen::Matrix4d::Identity();
  R.topLeftCorner<3, 3>() << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return R;
}

/// The corpus models Choreonoid loads (reference `loaded: true`).
std::vector<fs::path> corpus_models() {
  std::vector<fs::path> models;
  if (!fs::exists(kCorpus / "reference")) return models;
  for (const auto& entry : fs::recursive_directory_iterator(kCorpus / "reference")) {
    const std::string p = entry.path().string();
    if (p.size() < 9 || p.compare(p.size() - 9, 9, ".ref.yaml") != 0) continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    if (text.str().find("\nloaded: true") == std::string::npos && text.str().rfind("loaded: true", 0) != 0) continue;
    std::string rel = fs::relative(entry.path(), kCorpus / "reference").generic_string();
    rel.replace(rel.size() - 9, 9, ".body");
    models.push_back(kCorpus / "choreonoid" / rel);
  }
  std::sort(models.begin(), models.end());
  return models;
}

struct Imported {
  std::map<std::string, const aiNode*> links;  ///< the node carrying the link's extras
};

/// Link nodes of an imported scene: the node named after the link whose parent is the model
/// node or another link node (a shape, frame or device named like a link is never one).
void collect_links(const aiNode* n, const std::set<std::string>& names, bool parent_is_link_or_model,
                   std::map<std::string, const aiNode*>& out) {
  const std::string name = n->mName.C_Str();
  const bool is_link = parent_is_link_or_model && names.count(name) && !out.count(name);
  if (is_link) out[name] = n;
  for (unsigned i = 0; i < n->mNumChildren; ++i) collect_links(n->mChildren[i], names, is_link, out);
}

Eigen::Matrix4d world_of(const aiNode* n) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  for (; n; n = n->mParent) M = to_eigen(n->mTransformation) * M;
  return M;
}

/// Triangles and vertices (in the link node's frame) of every mesh below `n` that belongs to
/// this link (stops at child link nodes).
void link_geometry(const aiScene* scene, const aiNode* n, const Eigen::Matrix4d& X,
                   const std::set<const aiNode*>& links, std::size_t& triangles, BoundingBox& box) {
  for (unsigned i = 0; i < n->mNumMeshes; ++i) {
    const aiMesh* m = scene->mMeshes[n->mMeshes[i]];
    triangles += m->mNumFaces;
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const Eigen::Vector4d p = X * Eigen::Vector4d(m->mVertices[v].x, m->mVertices[v].y, m->mVertices[v].z, 1);
      box.add(Eigen::Vector3d(p.head<3>()));
    }
  }
  for (unsigned c = 0; c < n->mNumChildren; ++c) {
    const aiNode* child = n->mChildren[c];
    if (links.count(child)) continue;
    link_geometry(scene, child, X * to_eigen(child->mTransformation), links, triangles, box);
  }
}

bool close(double a, double b, double tol) { return std::abs(a - b) <= tol * std::max(1.0, std::abs(b)); }

/// Re-reads the GLB of `path` with assimp and compares every link node's world transform at
/// zero joint positions (1e-6), triangle counts and visual boxes with the model.
void check_round_trip(const fs::path& path) {
  {
    CAPTURE(path.string());
    auto e = export_model(path);
    const Model& model = *e->model;
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFileFromMemory(e->main.data(), e->main.size(), 0, "glb");
    REQUIRE_MESSAGE(scene, importer.GetErrorString());

    std::set<std::string> names;
    for (const Link& l : model.links) names.insert(l.name);
    std::map<std::string, const aiNode*> link_nodes;
    const aiNode* model_node = scene->mRootNode;
    if (model_node->mName != aiString(model.name) && model_node->mNumChildren == 1)
      model_node = model_node->mChildren[0];
    REQUIRE(std::string(model_node->mName.C_Str()) == model.name);
    for (unsigned i = 0; i < model_node->mNumChildren; ++i)
      collect_links(model_node->mChildren[i], names, true, link_nodes);
    std::set<const aiNode*> link_set;
    for (auto& [n, p] : link_nodes) link_set.insert(p);

    CollectingSink quiet;
    std::size_t total_expected = 0, total_got = 0;
    for (std::size_t i = 0; i < model.links.size(); ++i) {
      const Link& link = model.links[i];
      CAPTURE(link.name);
      REQUIRE(link_nodes.count(link.name));
      const aiNode* n = link_nodes[link.name];
      // World transform at zero joint positions: the model node's Z-up -> Y-up turn times X_WL.
      const Eigen::Matrix4d want = z_up_to_y_up() * Eigen::Affine3d(e->derived.X_WL[i]).matrix();
      const Eigen::Matrix4d got = world_of(n);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) CHECK_MESSAGE(close(got(r, c), want(r, c), 1e-6), r << "," << c);

      std::size_t expected_triangles = 0;
      for (const Shape& shape : link.shapes)
        if (shape.visual) expected_triangles += compute_shape_local_mesh(model, shape, quiet).triangles.size();
      std::size_t triangles = 0;
      BoundingBox box;
      link_geometry(scene, n, Eigen::Matrix4d::Identity(), link_set, triangles, box);
      CHECK(triangles == expected_triangles);
      total_expected += expected_triangles;
      total_got += triangles;
      const BoundingBox& ref = e->derived.bounds[i].visual;
      CHECK(box.empty() == ref.empty());
      if (!ref.empty() && !box.empty()) {
        const double tol = 1e-5 * std::max(1.0, (ref.max - ref.min).norm());
        CHECK_MESSAGE((box.min - ref.min).cwiseAbs().maxCoeff() <= tol, box.min.transpose()
                                                                            << " vs " << ref.min.transpose());
        CHECK_MESSAGE((box.max - ref.max).cwiseAbs().maxCoeff() <= tol, box.max.transpose()
                                                                            << " vs " << ref.max.transpose());
      }
    }
    CHECK(total_got == total_expected);
  }
}

TEST_CASE("gltf: every corpus model round-trips through assimp's glTF importer") {
  const auto models = corpus_models();
  REQUIRE_MESSAGE(models.size() >= 40, "the shared corpus is missing at " << kCorpus);
  for (const fs::path& path : models) check_round_trip(path);
  MESSAGE(models.size() << " corpus models round-tripped");
}

TEST_CASE("gltf: sheared and mirrored shapes are baked and round-trip") {
  check_round_trip(kData / "sheared.body");
  check_round_trip(fs::path(BODYFMT_EXAMPLES_DIR) / "simpletank.body");
  check_round_trip(fs::path(BODYFMT_EXAMPLES_DIR) / "arm.body");
}

TEST_CASE("gltf: a recurring primitive reuses its mesh, and one that differs in any value does not") {
  check_round_trip(kData / "repeated_primitives.body");
}

TEST_CASE("gltf: losses are reported at their source lines, once each") {
  const fs::path path = kData / "losses.body";
  auto e = export_model(path);
  std::set<int> expected;
  std::ifstream in(path);
  std::string line;
  const std::regex marker("^[^#]+# loss");
  for (int n = 1; std::getline(in, line); ++n)
    if (std::regex_search(line, marker)) expected.insert(n);
  std::multiset<int> got;
  for (const Diagnostic& d : e->sink.diagnostics())
    if (d.rule_id == "export-loss") got.insert(d.location.line);
  CHECK(std::set<int>(got.begin(), got.end()) == expected);
  CHECK(got.size() == expected.size());
  CHECK(expected.size() == 6);
}

TEST_CASE("gltf: an axis that is not a unit vector is written as its direction and said at the axis") {
  // losses.body's ARM has joint_axis: [0, 2, 0] on line 36, its value at column 17 (bodycheck's
  // joint-axis-not-unit place); TRACK's Y is a unit vector and says nothing.
  auto e = export_model(kData / "losses.body");
  std::vector<std::pair<int, int>> changed;
  for (const Diagnostic& d : e->sink.diagnostics())
    if (d.rule_id == "export-value-changed") changed.emplace_back(d.location.line, d.location.column);
  CHECK(changed == std::vector<std::pair<int, int>>{{36, 17}});
}

TEST_CASE("gltf: a model glTF can express fully reports no loss") {
  auto e = export_model(kData / "textured.body");
  for (const Diagnostic& d : e->sink.diagnostics()) CHECK_MESSAGE(d.rule_id != "export-loss", d.message);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string quote(const fs::path& p) { return "'" + p.string() + "'"; }

TEST_CASE("gltf: body2gltf exit codes, --strict, .gltf files and atomic output") {
  const std::string tool = BODYFMT_BODY2GLTF;
  const fs::path dir = fs::temp_directory_path() / "bodyfmt_gltf_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // 0: written, nothing lost; byte-identical on a second run; .gltf with its .bin and image.
  const fs::path gltf = dir / "tex.gltf";
  CHECK(run(tool + " " + quote(kData / "textured.body") + " -o " + quote(gltf) + " -q 2> /dev/null") == 0);
  const std::string first = slurp(gltf), bin = slurp(dir / "tex.bin");
  CHECK(!bin.empty());
  CHECK(fs::exists(dir / "textures" / "tex" / "checker.png"));  // in a folder of its own per export
  CHECK(run(tool + " " + quote(kData / "textured.body") + " -o " + quote(gltf) + " -q 2> /dev/null") == 0);
  CHECK(slurp(gltf) == first);
  CHECK(slurp(dir / "tex.bin") == bin);
  // 1: written with losses.
  const fs::path lossy = dir / "losses.glb";
  CHECK(run(tool + " " + quote(kData / "losses.body") + " -o " + quote(lossy) + " 2> /dev/null") == 1);
  CHECK(slurp(lossy).compare(0, 4, "glTF") == 0);
  // 2 with --strict: nothing written, the existing file kept.
  { std::ofstream(lossy) << "old"; }
  CHECK(run(tool + " " + quote(kData / "losses.body") + " -o " + quote(lossy) + " --strict 2> /dev/null") == 2);
  CHECK(slurp(lossy) == "old");
  // 2: an output that is neither .glb nor .gltf.
  CHECK(run(tool + " " + quote(kData / "textured.body") + " -o " + quote(dir / "x.obj") + " 2> /dev/null") == 2);
  CHECK(!fs::exists(dir / "x.obj"));
  // --collision and --both together are a usage error.
  CHECK(run(tool + " " + quote(kData / "textured.body") + " -o " + quote(dir / "y.glb") +
            " --collision --both 2> /dev/null") == 2);
  fs::remove_all(dir);
}

TEST_CASE("gltf: output is byte-identical across runs, GLB and .gltf") {
  const fs::path tank = fs::path(BODYFMT_EXAMPLES_DIR) / "simpletank.body";
  CHECK(export_model(tank)->main == export_model(tank)->main);
  auto a = export_model(kData / "textured.body", {}, "t.gltf");
  auto b = export_model(kData / "textured.body", {}, "t.gltf");
  CHECK(a->files == b->files);
  // .gltf: the JSON, one .bin and the texture, all staged in the same OutputSet.
  CHECK(a->files.size() == 3);
  CHECK(a->files.count("t.bin"));
  CHECK(a->files.count("textures/t/checker.png"));
}

TEST_CASE("gltf: link extras, root Y-up node, materials and the textured mesh") {
  auto e = export_model(kData / "losses.body");
  Json doc = json_of(e->main);
  const Json& nodes = doc["nodes"];
  const Json* arm = nullptr;
  for (const Json& n : nodes.items())
    if (n.find("name")->string() == "ARM") arm = &n;
  REQUIRE(arm);
  const Json& x = *arm->find("extras");
  CHECK(x.find("joint_type")->string() == "revolute");
  CHECK(x.find("joint_id")->number() == 3);
  CHECK(x.find("joint_axis")->items()[1].number() == doctest::Approx(1.0));  // normalised [0, 2, 0]
  CHECK(x.find("joint_range")->items()[0].number() == doctest::Approx(-kPi / 2));
  CHECK(x.find("joint_range")->items()[1].number() == doctest::Approx(kPi / 4));
  CHECK(x.find("joint_velocity_range")->items()[0].is_null());  // unlimited
  // The first node is the model's, turning Body's +Z onto glTF's +Y.
  CHECK(nodes.items()[0].find("name")->string() == "Losses");
  CHECK(nodes.items()[0].find("rotation")->items()[0].number() == doctest::Approx(-std::sqrt(0.5)));
  CHECK(doc.find("extensionsUsed")->items().size() == 1);  // KHR_lights_punctual only

  auto t = export_model(kData / "textured.body");
  Json tdoc = json_of(t->main);
  REQUIRE(tdoc.find("materials"));
  CHECK(tdoc["materials"].items().size() == 1);  // assimp's default material is gone
  const Json& mat = tdoc["materials"].items()[0];
  CHECK(mat.find("alphaMode")->string() == "BLEND");
  CHECK(mat.find("pbrMetallicRoughness")->find("baseColorFactor")->items()[3].number() == doctest::Approx(0.75));
  CHECK(mat.find("pbrMetallicRoughness")->find("baseColorTexture"));
  CHECK(tdoc["images"].items()[0].find("mimeType")->string() == "image/png");
  CHECK(!tdoc.find("extensionsUsed"));
}

TEST_CASE("gltf: nodes are written depth-first, as assimp writes a node tree, each with one parent") {
  // SR1's WAIST has six frames before its shapes: in the writer's tables a shape comes after
  // all of its link's frames, in the glTF right after its own frame.
  auto e = export_model(kCorpus / "choreonoid" / "SR1" / "SR1.body");
  Json doc = json_of(e->main);
  const auto& nodes = doc["nodes"].items();
  const std::size_t meshes = doc["meshes"].items().size();
  REQUIRE(nodes.size() > 100);
  std::vector<int> parents(nodes.size(), -1);
  std::vector<std::size_t> subtree(nodes.size(), 1);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    if (const Json* mesh = nodes[i].find("mesh")) CHECK(static_cast<std::size_t>(mesh->integer()) < meshes);
    const Json* children = nodes[i].find("children");
    if (!children) continue;
    // Pre-order: the first child follows its parent, each further child its sibling's subtree.
    std::size_t next = i + 1;
    for (const Json& c : children->items()) {
      const auto k = static_cast<std::size_t>(c.integer());
      CHECK(k == next);
      REQUIRE(k < nodes.size());
      CHECK(parents[k] == -1);
      parents[k] = static_cast<int>(i);
      subtree[i] += subtree[k];
      next = k + subtree[k];
    }
  }
  CHECK(subtree[0] == nodes.size());  // everything hangs below the model node
  CHECK(std::count(parents.begin(), parents.end(), -1) == 1);
  CHECK(doc["scenes"].items()[0].find("nodes")->items()[0].integer() == 0);
  // WAIST/frame1 (z = 0.0955) holds WAIST/frame2, which holds the shape WAIST/shape1; in the
  // writer's tables frame3..frame5 come between them.
  bool found = false;
  for (std::size_t i = 0; i + 2 < nodes.size(); ++i) {
    if (nodes[i].find("name")->string() != "WAIST/frame1") continue;
    found = true;
    CHECK(nodes[i].find("translation")->items()[2].number() == doctest::Approx(0.0955));
    CHECK(nodes[i + 1].find("name")->string() == "WAIST/frame2");
    CHECK(nodes[i + 2].find("name")->string() == "WAIST/shape1");
    CHECK(parents[i + 2] == static_cast<int>(i + 1));
    CHECK(nodes[i + 2].find("mesh"));
  }
  CHECK(found);
}

/// The direction a camera node looks in Body's world frame (undoing the Y-up node).
Eigen::Vector3d camera_forward(const std::string& glb, const std::string& camera) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(glb.data(), glb.size(), 0, "glb");
  REQUIRE(scene);
  const aiNode* n = scene->mRootNode->FindNode(camera.c_str());
  REQUIRE(n);
  const Eigen::Matrix4d M = z_up_to_y_up().inverse() * world_of(n);
  return (M.topLeftCorner<3, 3>() * Eigen::Vector3d(0, 0, -1)).normalized();
}

TEST_CASE("gltf: cameras face where Choreonoid's camera faces") {
  // SimpleTank's camera looks forward along +X (Rx(90) Ry(-90) on a gl optical frame).
  auto tank = export_model(fs::path(BODYFMT_EXAMPLES_DIR) / "simpletank.body");
  CHECK((camera_forward(tank->main, "Camera") - Eigen::Vector3d(1, 0, 0)).norm() < 1e-6);
  Json doc = json_of(tank->main);
  const Json& cam = doc["cameras"].items()[0];
  CHECK(cam.find("perspective")->find("yfov")->number() == doctest::Approx(65 * kPi / 180));  // landscape
  CHECK(cam.find("perspective")->find("aspectRatio")->number() == doctest::Approx(320.0 / 240.0));

  // A cv camera with no rotation looks along its frame's +Z; portrait: the 60 degrees span
  // the image width, so yfov = 2 atan(tan 30 deg * 400 / 200).
  auto e = export_model(kData / "losses.body");
  CHECK((camera_forward(e->main, "EYE") - Eigen::Vector3d(0, 0, 1)).norm() < 1e-6);
  Json ldoc = json_of(e->main);
  const Json& eye = ldoc["cameras"].items()[0];
  CHECK(eye.find("perspective")->find("yfov")->number() == doctest::Approx(2 * std::atan(std::tan(kPi / 6) * 2)));
}

TEST_CASE("gltf: optical_frame_rotation turns the camera as in Choreonoid (TankBody's Kinect looks forward)") {
  const fs::path tank = kCorpus / "choreonoid" / "Tank" / "TankBody.body";
  if (!fs::exists(tank)) return;
  auto e = export_model(tank);
  CHECK((camera_forward(e->main, "Kinect") - Eigen::Vector3d(1, 0, 0)).norm() < 1e-6);
}

TEST_CASE("gltf: a spot light shines along its direction with its cone angles") {
  auto tank = export_model(fs::path(BODYFMT_EXAMPLES_DIR) / "simpletank.body");
  Json doc = json_of(tank->main);
  const Json& light = doc["extensions"]["KHR_lights_punctual"]["lights"].items()[0];
  CHECK(light.find("type")->string() == "spot");
  CHECK(light.find("spot")->find("innerConeAngle")->number() == doctest::Approx(36 * kPi / 180));
  CHECK(light.find("spot")->find("outerConeAngle")->number() == doctest::Approx(40 * kPi / 180));
  CHECK((camera_forward(tank->main, "Light") - Eigen::Vector3d(1, 0, 0)).norm() < 1e-6);
}

TEST_CASE("gltf: light intensity is Choreonoid's factor in candela, a light that is off gives 0") {
  auto e = export_model(kData / "lights.body");
  Json doc = json_of(e->main);
  const Json& lights = doc["extensions"]["KHR_lights_punctual"]["lights"];
  std::map<std::string, const Json*> light_of, node_of;
  for (const Json& n : doc["nodes"].items()) {
    if (const Json* ext = n.find("extensions")) {
      const auto index = static_cast<std::size_t>(ext->find("KHR_lights_punctual")->find("light")->number());
      light_of[n.find("name")->string()] = &lights.items()[index];
      node_of[n.find("name")->string()] = &n;
    }
  }
  REQUIRE(light_of.size() == 2);
  // lights.body: Bulb intensity 0.6, colour (1, 0.5, 0.25) -> 0.6 cd, the same colour.
  const Json& bulb = *light_of.at("Bulb");
  CHECK(bulb.find("type")->string() == "point");
  CHECK(bulb.find("intensity")->number() == 0.6);
  CHECK(bulb.find("color")->items()[1].number() == 0.5);
  CHECK(bulb.find("color")->items()[2].number() == 0.25);
  CHECK(!node_of.at("Bulb")->find("extras")->find("intensity"));
  // Torch is off: Choreonoid does not light with it, so neither does the viewer; extras keep 0.8.
  const Json& torch = *light_of.at("Torch");
  CHECK(torch.find("type")->string() == "spot");
  CHECK(torch.find("intensity")->number() == 0.0);
  const Json& extras = *node_of.at("Torch")->find("extras");
  CHECK(extras.find("on")->boolean() == false);
  CHECK(extras.find("intensity")->number() == 0.8);
}

TEST_CASE("gltf: --both puts a hidden collision group beside the visual one") {
  GltfOptions both;
  both.geometry = GeometrySet::kBoth;
  auto e = export_model(fs::path(BODYFMT_EXAMPLES_DIR) / "simpletank.body", both);
  Json doc = json_of(e->main);
  bool visual = false, collision = false;
  for (const Json& n : doc["nodes"].items()) {
    const std::string name = n.find("name")->string();
    if (name == "CHASSIS/visual") visual = true;
    if (name == "CHASSIS/collision") collision = n.find("extras")->find("hidden")->boolean();
  }
  CHECK(visual);
  CHECK(collision);
}

TEST_CASE("gltf: the JSON model parses, keeps order and writes deterministic numbers") {
  auto j = Json::parse(R"({"b":[1,2.5,-0,1e-7,"x\"\u00e9"],"a":{"t":true,"n":null}})");
  REQUIRE(j);
  CHECK(j->dump() == "{\"b\":[1,2.5,0,1e-07,\"x\\\"\xC3\xA9\"],\"a\":{\"t\":true,\"n\":null}}");
  CHECK(!Json::parse("{\"a\":1,}"));
  CHECK(!Json::parse("[1 2]"));
  CHECK(!Json::parse("\"open"));
  CHECK(Json(0.1).dump() == "0.1");
  // Raw text goes out as it is (node extras are kept as text from writer to output).
  Json o = Json::object();
  o["x"] = Json::raw("{\"k\":[1,null]}");
  o["y"] = 2;
  CHECK(o.dump() == "{\"x\":{\"k\":[1,null]},\"y\":2}");
}

}  // namespace
}  // namespace bodyfmt::gltf
