// The key table (libbodyfmt body_keys.h) that bodyls's hover and completion read and the
// loader takes its known keys from: docs/keys.md is generated from it, and every key it lists
// is one the loader reads.

#include <bodyfmt/body_keys.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

/// The findings that say a key is not one the loader reads.
std::set<std::string> unread_keys(const std::string& text) {
  bodyfmt::CollectingSink sink;
  bodyfmt::LoadOptions options;
  options.load_meshes = false;
  (void)bodyfmt::load_body_string(text, "/tmp/keys.body", options, sink);
  std::set<std::string> found;
  for (const bodyfmt::Diagnostic& d : sink.diagnostics())
    if (d.rule_id.rfind("load-unknown", 0) == 0 || d.rule_id == "load-info-key") found.insert(d.message);
  return found;
}

/// `key: value` lines for every key of `id` but its type (and those written by the caller),
/// at `indent`.
std::string keys_of(const std::string& id, const std::string& indent) {
  const bodyfmt::BodyNode* node = bodyfmt::find_body_node(id);
  REQUIRE_MESSAGE(node, id);
  std::string out;
  for (const bodyfmt::BodyKey& key : node->keys)
    if (key.name != "type" && key.name != "elements" && key.name != "fragment" && key.name != "format" &&
        key.name != "numJoints" && key.name != "name")
      out += indent + std::string(key.name) + ": 0\n";
  return out;
}

}  // namespace

TEST_CASE("lsp features: docs/keys.md equals the key table (regenerate with keys_doc)") {
  const fs::path doc = fs::path(BODYFMT_EXAMPLES_DIR).parent_path() / "docs" / "keys.md";
  REQUIRE(fs::exists(doc));
  CHECK_MESSAGE(read(doc) == bodyfmt::body_keys_markdown(),
                "docs/keys.md is stale: run ./build/keys_doc > docs/keys.md");
}

TEST_CASE("lsp features: every key of the key table is one the loader reads") {
  const std::string header = "format: ChoreonoidBody\nformat_version: 2.0\n";
  CHECK(unread_keys(header + "links:\n  - name: a\n" + keys_of("link", "    ")).empty());
  CHECK(unread_keys(header + "links:\n  - name: a\n    elements:\n      - type: Shape\n" +
                    keys_of("element:Shape", "        "))
            .empty());
  for (const char* type : {"Box", "Sphere", "Cylinder", "Cone", "Capsule", "ElevationGrid", "IndexedFaceSet"}) {
    CAPTURE(type);
    CHECK(unread_keys(header + "links:\n  - name: a\n    elements:\n      - type: Shape\n        geometry:\n" +
                      "          type: " + type + "\n" + keys_of(std::string("geometry:") + type, "          "))
              .empty());
  }
  CHECK(unread_keys(header + "links:\n  - name: a\n    elements:\n      - type: RigidBody\n" +
                    keys_of("element:RigidBody", "        "))
            .empty());
  for (const char* type :
       {"ForceSensor", "RateGyroSensor", "AccelerationSensor", "IMU", "RangeSensor", "PointLight", "SpotLight"}) {
    CAPTURE(type);
    CHECK(unread_keys(header + "links:\n  - name: a\n    elements:\n      - type: " + type + "\n" +
                      keys_of(std::string("device:") + type, "        "))
              .empty());
  }
  CHECK(unread_keys(header + "links:\n  - name: a\n    elements:\n      - type: Camera\n        format: COLOR\n" +
                    keys_of("device:Camera", "        "))
            .empty());
  CHECK(unread_keys(header + "links:\n  - name: a\n  - type: ContinuousTrack\n    name: t\n    parent: a\n" +
                    "    numJoints: 3\n" + keys_of("link:ContinuousTrack", "    "))
            .empty());
  CHECK(unread_keys(header + "links:\n  - name: a\n    elements:\n      - type: Shape\n        appearance:\n" +
                    "          material:\n" + keys_of("material", "            "))
            .empty());
  // And a key the table does not have is reported, with the table's key as the guess.
  const auto typo = unread_keys(header + "links:\n  - name: a\n    joint_tpye: free\n");
  REQUIRE(typo.size() == 1);
  CHECK(typo.begin()->find("joint_tpye") != std::string::npos);
}

TEST_CASE("lsp features: the key table's nodes have distinct ids, keys, meanings and enumeration defaults") {
  std::set<std::string> ids;
  for (const bodyfmt::BodyNode& node : bodyfmt::body_nodes()) {
    CAPTURE(node.id);
    CHECK(ids.insert(std::string(node.id)).second);
    std::set<std::string> names;
    for (const bodyfmt::BodyKey& key : node.keys) {
      CAPTURE(key.name);
      CHECK(names.insert(std::string(key.name)).second);
      CHECK(!key.meaning.empty());
    }
    CHECK(node.names.size() == node.keys.size());
  }
}
