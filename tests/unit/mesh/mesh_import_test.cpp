// Mesh import against the Choreonoid corpus: reference bounding boxes, every corpus mesh file,
// diagnostics and the parse-once cache.
#include <bodyfmt/mesh_import.h>
#include <doctest/doctest.h>

#include "mesh_test_support.h"

#include <filesystem>
#include <vector>

using namespace bodyfmt;
using namespace mesh_test;

namespace {

struct LinkMesh {
  const char* link;
  const char* file;  // relative to the corpus
  const char* node;
};

void check_against_reference(const char* ref_file, const std::vector<LinkMesh>& links,
                             const std::vector<std::string>& detached = {}) {
  MeshCache cache;
  for (const LinkMesh& l : links) {
    CAPTURE(std::string(l.link));
    CollectingSink sink;
    MeshImportOptions options;
    options.node = l.node;
    options.detached_nodes = detached;
    auto asset = cache.get(kCorpus + l.file, options, sink, {"test.body", 1, 1});
    REQUIRE(asset);
    CHECK(sink.error_count() == 0);
    const auto ref = reference_visual_bbox(ref_file, l.link);
    REQUIRE(ref);
    const BoundingBox box = box_of(*asset);
    INFO("ours " << to_string(box) << " reference " << to_string(*ref));
    CHECK(boxes_match(box, *ref));
  }
}

}  // namespace

TEST_CASE("mesh import: UR5 COLLADA parts are in metres, Z-up, like Choreonoid") {
  check_against_reference("UniversalRobots/UR5.ref.yaml", {{"BASE", "UniversalRobots/UR5/base.dae", ""},
                                                           {"SHOULDER", "UniversalRobots/UR5/shoulder.dae", ""},
                                                           {"UPPER_ARM", "UniversalRobots/UR5/upperarm.dae", ""},
                                                           {"FOREARM", "UniversalRobots/UR5/forearm.dae", ""},
                                                           {"WRIST1", "UniversalRobots/UR5/wrist1.dae", ""},
                                                           {"WRIST2", "UniversalRobots/UR5/wrist2.dae", ""}});
}

TEST_CASE("mesh import: GR001 STL parts match the reference visual_bbox") {
  std::vector<LinkMesh> links;
  static const char* names[] = {"WAIST",        "R_HIP_Y",      "R_HIP_R",  "R_HIP_P",      "R_KNEE_P",     "R_ANKLE_P",
                                "R_ANKLE_R",    "L_HIP_Y",      "L_HIP_R",  "L_HIP_P",      "L_KNEE_P",     "L_ANKLE_P",
                                "L_ANKLE_R",    "CHEST_P",      "NECK_Y",   "R_SHOULDER_P", "R_SHOULDER_R", "R_ELBOW_P",
                                "L_SHOULDER_P", "L_SHOULDER_R", "L_ELBOW_P"};
  static std::vector<std::string> files;
  files.clear();
  for (const char* n : names) files.push_back(std::string("GR001/parts/") + n + ".stl");
  for (std::size_t i = 0; i < files.size(); ++i) links.push_back({names[i], files[i].c_str(), ""});
  check_against_reference("GR001/GR001.ref.yaml", links);
}

TEST_CASE("mesh import: PA10 VRML parts (no #VRML header) match the reference visual_bbox") {
  check_against_reference("PA10/PA10.ref.yaml", {{"BASE", "PA10/parts/BASE.wrl", ""},
                                                 {"J1", "PA10/parts/J1.wrl", ""},
                                                 {"J2", "PA10/parts/J2.wrl", ""},
                                                 {"J3", "PA10/parts/J3.wrl", ""},
                                                 {"J4", "PA10/parts/J4.wrl", ""},
                                                 {"J5", "PA10/parts/J5.wrl", ""},
                                                 {"J6", "PA10/parts/J6.wrl", ""},
                                                 {"J7", "PA10/parts/J7.wrl", ""},
                                                 {"HAND_L", "PA10/parts/HAND_L.wrl", ""},
                                                 {"HAND_R", "PA10/parts/HAND_R.wrl", ""}});
}

TEST_CASE("mesh import: tank.wrl fragments are re-centred (spec 9.4)") {
  check_against_reference("Tank/TankBody.ref.yaml",
                          {{"CHASSIS", "Tank/resource/tank.wrl", "CHASSIS"},
                           {"TURRET_Y", "Tank/resource/tank.wrl", "TURRET_Y"},
                           {"TURRET_P", "Tank/resource/tank.wrl", "TURRET_P"}},
                          {"CHASSIS", "TURRET_Y", "TURRET_P"});
  // Alone, TURRET_Y is the whole Transform, TURRET_P included (which reaches x = 0.3).
  CollectingSink sink;
  MeshImportOptions alone;
  alone.node = "TURRET_Y";
  auto whole = import_mesh(kCorpus + "Tank/resource/tank.wrl", alone, sink, {});
  REQUIRE(whole);
  CHECK(box_of(*whole).max.x() == doctest::Approx(0.3).epsilon(1e-3));
}

TEST_CASE("mesh import: tank.wrl WHEEL_L0 (a Transform and a Shape of that name) is centred") {
  CollectingSink sink;
  MeshImportOptions options;
  options.node = "WHEEL_L0";
  auto asset = import_mesh(kCorpus + "Tank/resource/tank.wrl", options, sink, {});
  REQUIRE(asset);
  CHECK(sink.error_count() == 0);
  // A wheel centred on the link origin: the Transform's translation is gone.
  const BoundingBox box = box_of(*asset);
  const Eigen::Vector3d centre = (box.min + box.max) / 2;
  CHECK(centre.norm() < 1e-3);
  CHECK(box.max.x() - box.min.x() > 0.05);
}

TEST_CASE("mesh import: every corpus mesh file imports without error") {
  std::vector<std::string> failures;
  int count = 0;
  MeshCache cache;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kCorpus)) {
    std::string ext = entry.path().extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".wrl" && ext != ".stl" && ext != ".obj" && ext != ".dae") continue;
    ++count;
    CollectingSink sink;
    auto asset = cache.get(entry.path().string(), {}, sink, {});
    if (!asset || sink.error_count() > 0 || triangle_count(*asset) == 0) {
      std::string why = sink.diagnostics().empty() ? "no triangles" : format_diagnostic(sink.diagnostics().front());
      failures.push_back(entry.path().string() + ": " + why);
    }
  }
  MESSAGE(count << " corpus mesh files imported");
  for (const auto& f : failures) MESSAGE(f);
  CHECK(count > 0);
  CHECK(failures.empty());
}

TEST_CASE("mesh import: a missing node is reported") {
  CollectingSink sink;
  MeshImportOptions options;
  options.node = "NO_SUCH_NODE";
  const SourceLocation where{"Tank.body", 12, 7};
  auto asset = import_mesh(kCorpus + "Tank/resource/tank.wrl", options, sink, where);
  CHECK_FALSE(asset);
  REQUIRE(sink.has("mesh-node-not-found"));
  CHECK(sink.diagnostics().back().location == where);
  CHECK(sink.diagnostics().back().message.find("NO_SUCH_NODE") != std::string::npos);
}

TEST_CASE("mesh import: a missing file is reported with its resolved path") {
  CollectingSink sink;
  const std::string path = std::string(BODYFMT_TEST_DATA_DIR) + "/mesh/../mesh/nowhere.stl";
  const SourceLocation where{"robot.body", 3, 9};
  auto asset = import_mesh(path, {}, sink, where);
  CHECK_FALSE(asset);
  REQUIRE(sink.has("mesh-file-missing"));
  const Diagnostic& d = sink.diagnostics().front();
  CHECK(d.location == where);
  CHECK(d.message.find(std::string(BODYFMT_TEST_DATA_DIR) + "/mesh/nowhere.stl") != std::string::npos);
}

TEST_CASE("mesh import: an unsupported extension is reported") {
  CollectingSink sink;
  auto asset = import_mesh(std::string(BODYFMT_TEST_DATA_DIR) + "/mesh/not_a_mesh.xyz", {}, sink, {"a.body", 1, 1});
  CHECK_FALSE(asset);
  CHECK(sink.has("mesh-format-unsupported"));
}

TEST_CASE("mesh import: the cache parses a file once for many links and nodes") {
  MeshCache cache;
  CollectingSink sink;
  const std::string tank = kCorpus + "Tank/resource/tank.wrl";
  MeshImportOptions chassis;
  chassis.node = "CHASSIS";
  auto a = cache.get(tank, chassis, sink, {});
  auto b = cache.get(tank, chassis, sink, {});
  MeshImportOptions wheel;
  wheel.node = "WHEEL_L0";
  auto c = cache.get(tank, wheel, sink, {});
  auto d = cache.get(kCorpus + "Tank/../Tank/resource/tank.wrl", {}, sink, {});
  REQUIRE(a);
  REQUIRE(c);
  REQUIRE(d);
  CHECK(a == b);  // the same shared asset
  CHECK(a != c);
  CHECK(cache.files_parsed() == 1);
  CHECK(sink.error_count() == 0);

  // Failures are cached too, and reported once.
  CollectingSink missing;
  CHECK_FALSE(cache.get(kCorpus + "none.stl", {}, missing, {}));
  CHECK_FALSE(cache.get(kCorpus + "none.stl", {}, missing, {}));
  CHECK(missing.diagnostics().size() == 1);
}

TEST_CASE("mesh import: metadata scales and turns Y-up meshes to Z-up (OBJ through assimp)") {
  const std::string obj = std::string(BODYFMT_TEST_DATA_DIR) + "/mesh/square.obj";
  CollectingSink sink;
  auto plain = import_mesh(obj, {}, sink, {});
  REQUIRE(plain);
  REQUIRE(plain->parts.size() == 1);
  CHECK(plain->parts[0].mesh.triangles.size() == 2);
  REQUIRE(plain->parts[0].material);
  CHECK(plain->parts[0].material->diffuse_color.isApprox(Eigen::Vector3d(1, 0, 0)));
  CHECK(plain->parts[0].material->specular_exponent == doctest::Approx(50));

  MeshImportOptions options;
  options.length_scale = 0.001;
  options.y_up = true;
  auto turned = import_mesh(obj, options, sink, {});
  REQUIRE(turned);
  const BoundingBox box = box_of(*turned);
  // Mesh X (2 units) becomes Y, mesh Y (1 unit) becomes Z.
  CHECK(box.max.x() == doctest::Approx(0));
  CHECK(box.max.y() == doctest::Approx(0.002));
  CHECK(box.max.z() == doctest::Approx(0.001));
  CHECK(sink.error_count() == 0);
}
