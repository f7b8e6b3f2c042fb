// bodyls's language features (tools/bodyls/features). Expected values come from outside the
// code under test: masses and world frames from Choreonoid's reference values
// (corpus/reference), angles computed here from body-format-spec §3, keys and defaults from
// the spec's tables.

#include <language_features.h>

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/load.h>
#include <bodyfmt/yaml.h>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace bodyfmt::lsp;

namespace {

const std::string kCorpus = std::string(BODYFMT_SHARED_DIR) + "/corpus/choreonoid/";
const std::string kReference = std::string(BODYFMT_SHARED_DIR) + "/corpus/reference/";
constexpr double kPi = 3.14159265358979323846;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

/// The 1-based line and byte column of the `nth` occurrence of `needle` in `text`, plus `shift`.
TextPoint point_of(const std::string& text, const std::string& needle, int shift = 0, int nth = 1) {
  std::size_t at = std::string::npos;
  for (int i = 0; i < nth; ++i) at = text.find(needle, at == std::string::npos ? 0 : at + 1);
  REQUIRE_MESSAGE(at != std::string::npos, needle);
  at += static_cast<std::size_t>(shift);
  const std::size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
  const int line = static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n')) + 1;
  const std::size_t begin = line_start == std::string::npos || at == 0 ? 0 : line_start + 1;
  return {line, static_cast<int>(at - begin) + 1};
}

/// The text a range covers (ranges are 1-based, byte columns).
std::string text_of(const std::string& text, TextRange r) {
  auto offset = [&](TextPoint p) {
    std::size_t o = 0;
    for (int line = 1; line < p.line; ++line) o = text.find('\n', o) + 1;
    return o + static_cast<std::size_t>(p.column - 1);
  };
  return text.substr(offset(r.begin), offset(r.end) - offset(r.begin));
}

Document doc(const std::string& text, const std::string& path = "/tmp/model.body") {
  Document d;
  d.path = path;
  d.text = text;
  return d;
}

std::vector<std::string> labels(const std::vector<CompletionItem>& items) {
  std::vector<std::string> out;
  for (const CompletionItem& i : items) out.push_back(i.label);
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

const std::string kSmall = R"(format: ChoreonoidBody
format_version: 2.0
name: small
extra_joints:
  - link1_name: hand
    link2_name: base
    joint_type: ball
links:
  - name: base
    joint_type: free
    mass: 2.0
    elements:
      - type: Shape
        geometry: { type: Box, size: [ 1, 1, 1 ] }
        appearance: &GREEN
          material: { diffuse: [ 0, 1, 0 ] }
  - name: arm
    parent: base
    joint_type: revolute
    joint_range: [ -90, 90 ]
    rotation: [ 0, 0, 1, 90 ]
    elements:
      - type: Shape
        geometry: { type: Sphere, radius: 0.1 }
        appearance: *GREEN
      - type: ForceSensor
        name: wrist_fs
  - name: hand
    parent: arm
    joint_type: prismatic
    joint_range: [ -0.5, 0.5 ]
)";

}  // namespace

TEST_CASE("lsp features: hover on a key gives its meaning, unit and default from the spec") {
  const Document d = doc(kSmall);
  auto h = hover(d, point_of(kSmall, "joint_type: free", 2));
  REQUIRE(h);
  CHECK(text_of(kSmall, h->range) == "joint_type");
  // body-format-spec §6.1/§6.2: default fixed; the five joint types.
  CHECK(h->markdown.find("default: fixed") != std::string::npos);
  CHECK(h->markdown.find("pseudo_continuous_track") != std::string::npos);
  h = hover(d, point_of(kSmall, "mass: 2.0"));
  REQUIRE(h);
  CHECK(h->markdown.find("unit: kg") != std::string::npos);
  h = hover(d, point_of(kSmall, "radius: 0.1", 1));  // a Sphere's radius, §9: 1 m by default
  REQUIRE(h);
  CHECK(h->markdown.find("unit: m; default: 1") != std::string::npos);
  h = hover(d, point_of(kSmall, "diffuse"));
  REQUIRE(h);
  CHECK(h->markdown.find("default: [1, 1, 1]") != std::string::npos);
}

TEST_CASE("lsp features: a key's hover gives an angle's unit as the file reads it and cites docs/keys.md") {
  // body-format-spec §3: format 2.0 reads degrees; format 1.0 reads radians with
  // angle_unit: radian. The unit named is the file's, not the word "angle" (issue 47).
  auto h = hover(doc(kSmall), point_of(kSmall, "joint_range"));
  REQUIRE(h);
  CHECK(h->markdown.find("unit: degree if revolute, else m") != std::string::npos);
  CHECK(h->markdown.find("unit: angle") == std::string::npos);
  const std::string radian =
      "format: ChoreonoidBody\nformatVersion: 1.0\nangleUnit: radian\nlinks:\n  - name: a\n    jointType: revolute\n"
      "    jointRange: [ -1.5, 1.5 ]\n";
  h = hover(doc(radian), point_of(radian, "jointRange"));
  REQUIRE(h);
  CHECK(h->markdown.find("unit: radian if revolute, else m") != std::string::npos);
  // The spec's sections are not installed; docs/keys.md is, under the heading named.
  CHECK(h->markdown.find("§") == std::string::npos);
  CHECK(h->markdown.find("docs/keys.md, \"Link\"") != std::string::npos);
  CHECK(read(fs::path(BODYFMT_EXAMPLES_DIR).parent_path() / "docs" / "keys.md").find("\n## Link\n") !=
        std::string::npos);
}

TEST_CASE("lsp features: a hover's plain text is its Markdown without markup, names kept as written") {
  // A link name with Markdown's characters: escaped in Markdown, verbatim in plain text.
  const std::string text =
      "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n"
      "  - { name: \"*arm_1*\", joint_type: free, mass: 2, inertia: [1,0,0,0,1,0,0,0,1] }\n";
  bodyfmt::CollectingSink sink;
  const auto model = bodyfmt::load_body_string(text, "/tmp/names.body", {}, sink);
  REQUIRE(model);
  Document d = doc(text);
  d.model = &*model;
  d.model_is_current = true;
  const auto h = hover(d, point_of(text, "*arm_1*", 1));
  REQUIRE(h);
  CHECK(h->plain_text.find("link *arm_1* — joint free") != std::string::npos);
  CHECK(h->markdown.find("**link \\*arm_1\\*** — joint free") != std::string::npos);
  CHECK(h->plain_text.find("**") == std::string::npos);
  const auto key = hover(d, point_of(text, "joint_type"));
  REQUIRE(key);
  CHECK(key->plain_text.rfind("joint_type (also jointType) — Link\n\n", 0) == 0);
  CHECK(key->markdown.rfind("**joint_type** (also `jointType`) — Link\n\n", 0) == 0);
}

TEST_CASE("lsp features: hover on a misspelt key names the key it is probably") {
  const std::string text = "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: a\n    jiont_type: free\n";
  const auto h = hover(doc(text), point_of(text, "jiont_type"));
  REQUIRE(h);
  CHECK(h->markdown.find("did you mean `joint_type`") != std::string::npos);
}

TEST_CASE("lsp features: hover on an angle gives degrees and radians as the file's format reads it") {
  // Format 2.0: degrees (body-format-spec §2.1, §3). 90 degrees = pi/2 rad.
  const Document d = doc(kSmall);
  auto h = hover(d, point_of(kSmall, "90 ]", 0, 2));  // rotation's 4th number
  REQUIRE(h);
  CHECK(text_of(kSmall, h->range) == "90");
  CHECK(h->markdown.find(fmt::format("90° = {:.10g} rad", kPi / 2)) != std::string::npos);
  // joint_range on a revolute joint: an angle; -90 degrees.
  h = hover(d, point_of(kSmall, "-90"));
  REQUIRE(h);
  CHECK(h->markdown.find(fmt::format("-90° = {:.10g} rad", -kPi / 2)) != std::string::npos);
  // An axis component of the rotation is no angle; a prismatic joint's range is metres.
  h = hover(d, point_of(kSmall, "rotation: [ 0, 0, 1", 18));
  REQUIRE(h);
  CHECK(h->markdown.find("axis component") != std::string::npos);
  h = hover(d, point_of(kSmall, "-0.5"));
  REQUIRE(h);
  CHECK(h->markdown.find("revolute") != std::string::npos);
  CHECK(h->markdown.find("rad") == std::string::npos);

  // Format 1.0 in radian mode: the number is radians; 1.5 rad = 85.94366927 degrees.
  const std::string radian =
      "format: ChoreonoidBody\nformatVersion: 1.0\nangleUnit: radian\nlinks:\n  - name: a\n    jointType: revolute\n"
      "    jointRange: [ -1.5, 1.5 ]\n";
  h = hover(doc(radian), point_of(radian, "1.5 ]"));
  REQUIRE(h);
  CHECK(h->markdown.find(fmt::format("{:.10g}° = 1.5 rad", 1.5 * 180 / kPi)) != std::string::npos);
  CHECK(h->markdown.find("85.94366927") != std::string::npos);

  // Format 2.0 with radian: the loader refuses the file.
  const std::string refused =
      "format: ChoreonoidBody\nformat_version: 2.0\nangle_unit: radian\nlinks:\n"
      "  - name: a\n    rotation: [ 1, 0, 0, 1.5 ]\n";
  h = hover(doc(refused), point_of(refused, "1.5"));
  REQUIRE(h);
  CHECK(h->markdown.find("does not load") != std::string::npos);
}

namespace {

struct RefLink {
  std::string parent;
  double mass = 0;
  std::vector<double> world;
};

std::vector<double> numbers(const bodyfmt::YamlNode& list) {
  std::vector<double> out;
  for (const bodyfmt::YamlNode& v : list.items()) out.push_back(std::stod(std::string(v.scalar())));
  return out;
}

/// Choreonoid's reference: each link's parent, mass and world position at the initial pose
/// (its root-relative position at zero joint values, placed by the root's initial pose).
std::map<std::string, RefLink> reference_links(const std::string& path, double& total_mass) {
  bodyfmt::CollectingSink sink;
  auto ref = bodyfmt::read_yaml_file(path, sink);
  REQUIRE(ref);
  total_mass = std::stod(std::string(ref->root().find("total_mass")->value.scalar()));
  const std::vector<double> root_p = numbers(ref->root().find("root_translation")->value);
  const std::vector<double> root_R = numbers(ref->root().find("root_rotation")->value);  // row-major
  REQUIRE(root_p.size() == 3);
  REQUIRE(root_R.size() == 9);
  std::map<std::string, RefLink> links;
  for (const bodyfmt::YamlNode& l : ref->root().find("links")->value.items()) {
    RefLink r;
    const auto parent = l.find("parent")->value;
    r.parent = parent.is_null() ? "" : std::string(parent.scalar());
    r.mass = std::stod(std::string(l.find("mass")->value.scalar()));
    const std::vector<double> w = numbers(l.find("world_translation_at_zero")->value);
    REQUIRE(w.size() == 3);
    for (int i = 0; i < 3; ++i)
      r.world.push_back(root_p[i] + root_R[3 * i] * w[0] + root_R[3 * i + 1] * w[1] + root_R[3 * i + 2] * w[2]);
    links[std::string(l.find("name")->value.scalar())] = r;
  }
  return links;
}

double subtree_mass(const std::map<std::string, RefLink>& links, const std::string& name) {
  double m = links.at(name).mass;
  for (const auto& [child, r] : links)
    if (r.parent == name) m += subtree_mass(links, child);
  return m;
}

}  // namespace

TEST_CASE("lsp features: hover on a link's name gives Choreonoid's mass, subtree mass and world frame (SR1)") {
  const std::string path = kCorpus + "SR1/SR1.body";
  bodyfmt::CollectingSink sink;
  const auto model = bodyfmt::load_body(path, {}, sink);
  REQUIRE(model);
  double total = 0;
  const auto ref = reference_links(kReference + "SR1/SR1.ref.yaml", total);
  Document d = doc(read(path), path);
  d.model = &*model;
  d.model_is_current = true;
  for (const std::string name : {"WAIST", "WAIST_R", "RARM_SHOULDER_P", "LLEG_ANKLE_R"}) {
    CAPTURE(name);
    const auto h = hover(d, point_of(d.text, "name: " + name + "\n", 6));
    REQUIRE(h);
    INFO(h->markdown);
    CHECK(text_of(d.text, h->range) == name);
    const RefLink& r = ref.at(name);
    CHECK(h->markdown.find(fmt::format("mass {:.6g} kg", r.mass)) != std::string::npos);
    CHECK(h->markdown.find(fmt::format("subtree {:.6g} kg", subtree_mass(ref, name))) != std::string::npos);
    CHECK(h->markdown.find(fmt::format("position [{:.6g}, {:.6g}, {:.6g}] m", r.world[0] + 0.0, r.world[1] + 0.0,
                                       r.world[2] + 0.0)) != std::string::npos);
  }
  // The root's subtree is the whole body: Choreonoid's total mass.
  const auto root = hover(d, point_of(d.text, "name: WAIST\n", 6));
  REQUIRE(root);
  CHECK(root->markdown.find(fmt::format("subtree {:.6g} kg", total)) != std::string::npos);
  CHECK(root->markdown.find("joint free") != std::string::npos);
}

TEST_CASE("lsp features: completion of keys leaves out those present and works on half-typed text") {
  // The last line is being typed: the text does not parse as YAML.
  const std::string text =
      "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: base\n    joint_type: free\n"
      "  - name: arm\n    parent: base\n    joi";
  auto items = labels(complete(doc(text), point_of(text, "    joi", 7, 2)));
  CHECK(has(items, "joint_type"));
  CHECK(has(items, "joint_axis"));
  CHECK(has(items, "max_joint_velocity"));
  CHECK(!has(items, "name"));
  CHECK(!has(items, "parent"));
  CHECK(!has(items, "format"));
  // A new item of the links list: link keys.
  const std::string item = "format: ChoreonoidBody\nlinks:\n  - name: base\n  - \n";
  items = labels(complete(doc(item), point_of(item, "  - \n", 4)));
  CHECK(has(items, "name"));
  CHECK(has(items, "parent"));
  // Top level, with format already written; a camelCase spelling counts as the key.
  const std::string top = "format: ChoreonoidBody\nformatVersion: 1.0\n\nlinks: []\n";
  items = labels(complete(doc(top), point_of(top, "\n\n", 1)));
  CHECK(has(items, "angle_unit"));
  CHECK(!has(items, "format"));
  CHECK(!has(items, "format_version"));
  CHECK(!has(items, "links"));
  // Inside a Box geometry, written as a flow mapping.
  const std::string box = "links:\n  - name: a\n    elements:\n      - type: Shape\n        geometry: { type: Box, ";
  items = labels(complete(doc(box), {5, static_cast<int>(std::string("        geometry: { type: Box, ").size()) + 1}));
  CHECK(has(items, "size"));
  CHECK(!has(items, "type"));
  CHECK(!has(items, "radius"));
}

TEST_CASE("lsp features: completion of enumerations, link names, anchors and files") {
  const Document d = doc(kSmall);
  // joint_type values (body-format-spec §6.2).
  std::string text = kSmall + "  - name: finger\n    parent: hand\n    joint_type: ";
  auto items = labels(complete(doc(text), point_of(text, "joint_type: ", 12, 5)));
  INFO(text);
  CHECK(items == std::vector<std::string>{"fixed", "free", "revolute", "prismatic", "pseudo_continuous_track"});
  // parent: every link name but the link's own.
  text = kSmall + "  - name: finger\n    parent: ";
  items = labels(complete(doc(text), point_of(text, "parent: ", 8, 3)));
  CHECK(items == std::vector<std::string>{"base", "arm", "hand"});
  // An element's type, a geometry's type, an actuation mode.
  text = "links:\n  - name: a\n    elements:\n      - type: Sh";
  items = labels(complete(doc(text), point_of(text, "Sh", 2)));
  CHECK(has(items, "Shape"));
  CHECK(has(items, "RigidBody"));
  CHECK(has(items, "ForceSensor"));
  text = "links:\n  - name: a\n    elements:\n      - type: Shape\n        geometry:\n          type: ";
  items = labels(complete(doc(text), point_of(text, "type: ", 6, 2)));
  CHECK(has(items, "Box"));
  CHECK(has(items, "Capsule"));
  CHECK(!has(items, "Shape"));
  text = "links:\n  - name: a\n    actuation_mode: ";
  items = labels(complete(doc(text), point_of(text, "mode: ", 6)));
  CHECK(has(items, "joint_effort"));
  CHECK(has(items, "joint_velocity"));
  // Anchors after '*'.
  text = kSmall + "  - name: x\n    parent: base\n    elements:\n      - type: Shape\n        appearance: *";
  const auto anchors = complete(doc(text), point_of(text, ": *", 3, 1 + 1));
  CHECK(labels(anchors) == std::vector<std::string>{"GREEN"});
  // Files after uri:, relative to the document's folder.
  const fs::path dir = fs::temp_directory_path() / "bodyls_features_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "arm.stl") << "solid\n";
  std::ofstream(dir / "meshes" / "hand.stl") << "solid\n";
  text = "links:\n  - name: a\n    elements:\n      - type: Resource\n        uri: meshes/";
  const auto files = complete(doc(text, (dir / "model.body").string()), point_of(text, "meshes/", 7));
  CHECK(labels(files) == std::vector<std::string>{"meshes/arm.stl", "meshes/hand.stl"});
  REQUIRE(!files.empty());
  CHECK(text_of(text, files[0].replace) == "meshes/");
  fs::remove_all(dir);
}

TEST_CASE("lsp features: a device's own keys, values and angles") {
  const std::string text =
      "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: a\n    elements:\n"
      "      - type: Camera\n        name: eye\n        field_of_view: 60\n        format: ";
  // §10.2: COLOR makes a Camera, the four others a RangeCamera.
  auto items = labels(complete(doc(text), point_of(text, "format: ", 8, 2)));
  CHECK(items == std::vector<std::string>{"COLOR", "DEPTH", "COLOR_DEPTH", "POINT_CLOUD", "COLOR_POINT_CLOUD"});
  const std::string keys =
      "format: ChoreonoidBody\nlinks:\n  - name: a\n    elements:\n      - type: SpotLight\n"
      "        beam_width: 30\n        \n";
  items = labels(complete(doc(keys), point_of(keys, "        \n", 8)));
  CHECK(has(items, "cut_off_angle"));
  CHECK(has(items, "intensity"));
  CHECK(!has(items, "beam_width"));
  CHECK(!has(items, "width"));
  // field_of_view is an angle: 60 degrees = pi/3 rad.
  const auto h = hover(doc(text), point_of(text, "60"));
  REQUIRE(h);
  CHECK(h->markdown.find(fmt::format("60° = {:.10g} rad", kPi / 3)) != std::string::npos);
}

TEST_CASE("lsp features: definition of a parent, an alias and a uri") {
  const Document d = doc(kSmall);
  auto defs = definition(d, point_of(kSmall, "parent: base", 9));
  REQUIRE(defs.size() == 1);
  CHECK(defs[0].range.begin.line == point_of(kSmall, "- name: base").line);
  CHECK(text_of(kSmall, defs[0].range) == "base");
  defs = definition(d, point_of(kSmall, "*GREEN", 2));
  REQUIRE(defs.size() == 1);
  CHECK(text_of(kSmall, defs[0].range) == "&GREEN");
  // A SubBody's model file.
  const std::string path = kCorpus + "Tank/Tank.body";
  const std::string tank = read(path);
  const auto pos = tank.find("TankBody.body");
  REQUIRE(pos != std::string::npos);
  defs = definition(doc(tank, path), point_of(tank, "TankBody.body", 2));
  REQUIRE(defs.size() == 1);
  CHECK(fs::equivalent(defs[0].file, kCorpus + "Tank/TankBody.body"));
}

TEST_CASE("lsp features: definition of a link a SubBody file defines, with prefixes, suffixes and nesting") {
  // Tank.body's TRACK_L has `parent: CHASSIS`, a link of TankBody.body (line 8: "    name: CHASSIS").
  {
    const std::string path = kCorpus + "Tank/Tank.body";
    bodyfmt::CollectingSink sink;
    const auto model = bodyfmt::load_body(path, {}, sink);
    REQUIRE(model);
    Document d = doc(read(path), path);
    d.model = &*model;
    d.model_is_current = true;
    const auto defs = definition(d, point_of(d.text, "parent: CHASSIS", 9));
    REQUIRE(defs.size() == 1);
    CHECK(fs::equivalent(defs[0].file, kCorpus + "Tank/TankBody.body"));
    CHECK(defs[0].range.begin.line == 8);
    CHECK(defs[0].range.begin.column == 11);
    CHECK(defs[0].to_token_end);
  }
  // main.body includes arm.body (prefix L_, suffix _a), which includes hand.body (prefix H).
  const fs::path dir = fs::temp_directory_path() / "bodyls_definition_subbody_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "parts");
  std::ofstream(dir / "parts" / "hand.body") << "format: ChoreonoidBody\nformat_version: 2.0\nname: HAND\nlinks:\n"
                                                "  - { joint_name: \"\xC3\xB6\", name: F1, mass: 1 }\n";
  std::ofstream(dir / "parts" / "arm.body") << "format: ChoreonoidBody\nformat_version: 2.0\nname: ARM\nlinks:\n"
                                               "  - name: SHOULDER\n    mass: 1\n"
                                               "  - { name: \"WRIST3\", parent: SHOULDER, mass: 1 }\n"
                                               "  - type: SubBody\n    uri: hand.body\n    parent: WRIST3\n"
                                               "    prefix: H\n";
  const std::string main_text =
      "format: ChoreonoidBody\nformat_version: 2.0\nname: ROBOT\nlinks:\n  - name: BASE\n    joint_type: free\n    "
      "mass: 1\n"
      "  - { type: SubBody, uri: parts/arm.body, parent: BASE, prefix: L_, suffix: _a }\n"
      "  - { name: TOOL, parent: L_WRIST3_a, mass: 1 }\n"
      "  - { name: GRIP, parent: L_HF1_a, mass: 1 }\n"
      "extra_joints:\n  - { link1_name: L_HF1_a, link2_name: BASE, joint_type: ball }\n";
  const std::string main_path = (dir / "main.body").string();
  bodyfmt::CollectingSink sink;
  const auto model = bodyfmt::load_body_string(main_text, main_path, {}, sink);
  REQUIRE(model);
  Document d = doc(main_text, main_path);
  d.model = &*model;
  d.model_is_current = true;
  auto defs = definition(d, point_of(main_text, "L_WRIST3_a", 3));
  REQUIRE(defs.size() == 1);
  CHECK(fs::equivalent(defs[0].file, dir / "parts" / "arm.body"));
  CHECK(defs[0].range.begin.line == 7);  // "  - { name: \"WRIST3\"": the quote, byte column 13
  CHECK(defs[0].range.begin.column == 13);
  for (const std::string& at : {std::string("parent: L_HF1_a"), std::string("link1_name: L_HF1_a")}) {
    defs = definition(d, point_of(main_text, at, static_cast<int>(at.size()) - 2));
    REQUIRE(defs.size() == 1);
    CHECK(fs::equivalent(defs[0].file, dir / "parts" / "hand.body"));
    CHECK(defs[0].range.begin.line == 5);  // after "ö", two bytes: byte column 31
    CHECK(defs[0].range.begin.column == 31);
  }
  // A link of this text is found in it, once.
  defs = definition(d, point_of(main_text, "parent: BASE", 9));
  REQUIRE(defs.size() == 1);
  CHECK(defs[0].file == main_path);
  CHECK(!defs[0].to_token_end);
  CHECK(text_of(main_text, defs[0].range) == "BASE");
  // The name as the SubBody file writes it is no link of the composed model.
  std::string unprefixed = main_text;
  unprefixed.replace(unprefixed.find("L_WRIST3_a"), 10, "WRIST3");
  d.text = unprefixed;
  d.model_is_current = false;
  CHECK(definition(d, point_of(unprefixed, "parent: WRIST3", 9)).empty());
  fs::remove_all(dir);
}

TEST_CASE("lsp features: definition of a ContinuousTrack's link is its template's name") {
  const std::string text =
      "format: ChoreonoidBody\nformat_version: 2.0\nname: T\nlinks:\n  - name: BODY\n    joint_type: free\n    mass: "
      "1\n"
      "  - type: ContinuousTrack\n    name: SHOE\n    parent: BODY\n    numJoints: 4\n"
      "    jointOffset: [ 0.1, 0, 0 ]\n    joint_axis: Y\n    mass: 0.1\n"
      "  - { name: TIP, parent: SHOE3, mass: 0.1 }\n";
  bodyfmt::CollectingSink sink;
  const auto model = bodyfmt::load_body_string(text, "/tmp/track.body", {}, sink);
  REQUIRE(model);
  Document d = doc(text, "/tmp/track.body");
  d.model = &*model;
  d.model_is_current = true;
  auto defs = definition(d, point_of(text, "SHOE3", 2));
  REQUIRE(defs.size() == 1);
  CHECK(defs[0].file == "/tmp/track.body");
  CHECK(defs[0].range.begin.line == 9);  // "    name: SHOE"
  CHECK(defs[0].range.begin.column == 11);
  // A model of an older text cannot place anything in this one.
  d.model_is_current = false;
  CHECK(definition(d, point_of(text, "SHOE3", 2)).empty());
}

TEST_CASE("lsp features: references and rename of a link") {
  const Document d = doc(kSmall);
  auto refs = references(d, point_of(kSmall, "name: base", 7), false);
  // The extra joint's link2_name and parent: base, in file order.
  REQUIRE(refs.size() == 2);
  CHECK(refs[0].range.begin.line == point_of(kSmall, "link2_name: base").line);
  CHECK(refs[1].range.begin.line == point_of(kSmall, "parent: base").line);
  refs = references(d, point_of(kSmall, "parent: base", 9), true);
  CHECK(refs.size() == 3);

  std::string why;
  const auto range = prepare_rename(d, point_of(kSmall, "parent: arm", 9), why);
  REQUIRE(range);
  CHECK(text_of(kSmall, *range) == "arm");
  CHECK(!prepare_rename(d, point_of(kSmall, "joint_type: free", 13), why));
  CHECK(!why.empty());

  auto edits = rename_link(d, point_of(kSmall, "name: arm", 7), "upper_arm", why);
  REQUIRE(edits);
  REQUIRE(edits->size() == 2);  // its name and hand's parent
  std::string renamed = kSmall;
  // Apply from the end so that earlier offsets stay right.
  std::vector<TextEdit> sorted = *edits;
  std::sort(sorted.begin(), sorted.end(),
            [](const TextEdit& a, const TextEdit& b) { return a.where.range.begin.line > b.where.range.begin.line; });
  for (const TextEdit& e : sorted) {
    CHECK(text_of(renamed, e.where.range) == "arm");
    std::size_t o = 0;
    for (int line = 1; line < e.where.range.begin.line; ++line) o = renamed.find('\n', o) + 1;
    o += static_cast<std::size_t>(e.where.range.begin.column - 1);
    renamed.replace(o, 3, e.new_text);
  }
  CHECK(renamed.find("name: upper_arm") != std::string::npos);
  CHECK(renamed.find("parent: upper_arm") != std::string::npos);
  bodyfmt::CollectingSink sink;
  const auto model = bodyfmt::load_body_string(renamed, "/tmp/renamed.body", {}, sink);
  REQUIRE(model);
  CHECK(model->find_link("upper_arm") >= 0);
  CHECK(model->links[static_cast<std::size_t>(model->find_link("hand"))].parent == model->find_link("upper_arm"));

  CHECK(!rename_link(d, point_of(kSmall, "name: arm", 7), "hand", why));
  CHECK(why.find("already") != std::string::npos);
  CHECK(!rename_link(d, point_of(kSmall, "name: arm", 7), "", why));
  CHECK(!rename_link(d, point_of(kSmall, "name: arm", 7), "a\nb", why));
  // A name that is no plain scalar is written quoted.
  edits = rename_link(d, point_of(kSmall, "name: arm", 7), "arm: left", why);
  REQUIRE(edits);
  CHECK((*edits)[0].new_text == "\"arm: left\"");
}

TEST_CASE("lsp features: rename of a quoted link name replaces the name with its quotes") {
  // Block and flow, double and single quotes: the edit covers the whole quoted scalar, so the
  // renamed file loads with the new name wherever the old one was.
  const std::string text = R"(format: ChoreonoidBody
format_version: 2.0
name: q
links:
  - name: "base"
    joint_type: free
    mass: 1
  - { name: 'arm', parent: "base", joint_type: fixed, mass: 1 }
  - name: hand
    parent: 'arm'
    joint_type: fixed
    mass: 1
)";
  const Document d = doc(text);
  const auto offset = [&](const std::string& t, TextPoint p) {
    std::size_t o = 0;
    for (int line = 1; line < p.line; ++line) o = t.find('\n', o) + 1;
    return o + static_cast<std::size_t>(p.column - 1);
  };
  for (const auto& rename_case : {std::pair<TextPoint, std::string>{point_of(text, "name: \"base\"", 8), "base"},
                                  {point_of(text, "'arm', parent", 2), "arm"}}) {
    // Not a structured binding: clang 14 cannot capture one in CAPTURE's lambda.
    const TextPoint at = rename_case.first;
    const std::string& old_name = rename_case.second;
    CAPTURE(old_name);
    std::string why;
    const auto edits = rename_link(d, at, "renamed", why);
    REQUIRE(edits);
    std::vector<TextEdit> sorted = *edits;
    std::sort(sorted.begin(), sorted.end(), [&](const TextEdit& a, const TextEdit& b) {
      return offset(text, a.where.range.begin) > offset(text, b.where.range.begin);
    });
    std::string renamed = text;
    for (const TextEdit& e : sorted) {
      const std::size_t begin = offset(text, e.where.range.begin), end = offset(text, e.where.range.end);
      renamed.replace(begin, end - begin, e.new_text);
    }
    CAPTURE(renamed);
    bodyfmt::CollectingSink sink;
    const auto model = bodyfmt::load_body_string(renamed, "/tmp/renamed.body", {}, sink);
    REQUIRE(model);
    CHECK(sink.error_count() == 0);
    CHECK(model->find_link(old_name) < 0);
    CHECK(model->find_link("renamed") >= 0);
    CHECK(model->links.size() == 3);
  }
}

TEST_CASE("lsp features: document symbols are the link tree with elements and devices under their links") {
  const Document d = doc(kSmall);
  const auto symbols = document_symbols(d);
  REQUIRE(symbols.size() == 1);
  CHECK(symbols[0].kind == SymbolKind::kBody);
  CHECK(symbols[0].name == "small");
  REQUIRE(symbols[0].children.size() == 1);
  const Symbol& base = symbols[0].children[0];
  CHECK(base.name == "base");
  CHECK(base.detail == "free");
  CHECK(text_of(kSmall, base.selection) == "base");
  CHECK(text_of(kSmall, base.range).rfind("name: base", 0) == 0);
  REQUIRE(base.children.size() == 2);  // its Shape, then the link arm
  CHECK(base.children[0].kind == SymbolKind::kElement);
  const Symbol& arm = base.children[1];
  CHECK(arm.name == "arm");
  REQUIRE(arm.children.size() == 3);  // Shape, ForceSensor, hand
  CHECK(arm.children[1].kind == SymbolKind::kDevice);
  CHECK(arm.children[1].name == "wrist_fs");
  CHECK(arm.children[2].name == "hand");
  CHECK(arm.children[2].detail == "prismatic");
}

namespace {

bool inside(const std::string& text, TextPoint p) {
  if (p.line < 1 || p.column < 1) return false;
  std::size_t o = 0;
  for (int line = 1; line < p.line; ++line) {
    o = text.find('\n', o);
    if (o == std::string::npos) return false;
    ++o;
  }
  std::size_t end = text.find('\n', o);
  if (end == std::string::npos) end = text.size();
  return o + static_cast<std::size_t>(p.column - 1) <= end;
}

bool inside(const std::string& text, TextRange r) {
  return inside(text, r.begin) && inside(text, r.end) &&
         (r.begin.line < r.end.line || (r.begin.line == r.end.line && r.begin.column <= r.end.column));
}

void check_symbols(const std::string& text, const std::vector<Symbol>& symbols, int& bad) {
  for (const Symbol& s : symbols) {
    if (!inside(text, s.range) || !inside(text, s.selection)) ++bad;
    check_symbols(text, s.children, bad);
  }
}

}  // namespace

TEST_CASE("lsp features: every feature is total on corpus models cut and spliced at random points") {
  std::mt19937 random(38);
  std::vector<std::string> texts;
  for (const auto& entry : fs::recursive_directory_iterator(kCorpus))
    if (entry.path().extension() == ".body") texts.push_back(read(entry.path()));
  REQUIRE(texts.size() > 40);
  std::sort(texts.begin(), texts.end());
  int calls = 0, bad = 0;
  for (int round = 0; round < 120; ++round) {
    std::string text = texts[random() % texts.size()];
    // Cut it, and sometimes splice another model's text (or random bytes) in.
    text.resize(random() % (text.size() + 1));
    if (round % 3 == 1) {
      const std::string& other = texts[random() % texts.size()];
      const std::size_t from = random() % (other.size() + 1);
      text += other.substr(from, random() % 400);
    } else if (round % 3 == 2) {
      for (int i = 0; i < 40; ++i) text += "\n -:{[]}*&'\" #\t|>x"[random() % 17];
    }
    const Document d = doc(text, kCorpus + "SR1/cut.body");
    const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
    for (int k = 0; k < 8; ++k) {
      const TextPoint p{static_cast<int>(random() % static_cast<unsigned>(lines + 1)) + 1,
                        static_cast<int>(random() % 40)};
      ++calls;
      if (auto h = hover(d, p); h && !inside(text, h->range)) ++bad;
      for (const CompletionItem& c : complete(d, p))
        if (!inside(text, c.replace)) ++bad;
      for (const FileRange& r : definition(d, p))
        if (r.file == d.path && !inside(text, r.range)) ++bad;
      for (const FileRange& r : references(d, p, true))
        if (!inside(text, r.range)) ++bad;
      std::string why;
      if (auto r = prepare_rename(d, p, why); r && !inside(text, *r)) ++bad;
      if (auto edits = rename_link(d, p, "renamed_link", why))
        for (const TextEdit& e : *edits)
          if (!inside(text, e.where.range)) ++bad;
    }
    check_symbols(text, document_symbols(d), bad);
  }
  CHECK(calls == 960);
  CHECK(bad == 0);
}

TEST_CASE("lsp features: SimpleTank's symbols and angles, with elements in all three forms") {
  const std::string path = kCorpus + "Tank/SimpleTank.body";
  const Document d = doc(read(path), path);
  const auto symbols = document_symbols(d);
  REQUIRE(symbols.size() == 1);
  CHECK(symbols[0].name == "SimpleTank");
  REQUIRE(symbols[0].children.size() == 1);
  const Symbol& chassis = symbols[0].children[0];
  CHECK(chassis.name == "CHASSIS");
  std::vector<std::string> names;
  for (const Symbol& s : chassis.children) names.push_back(s.name);
  CHECK(names == std::vector<std::string>{"Shape", "TURRET_Y", "TRACK_L", "TRACK_R"});
  REQUIRE(chassis.children[1].children.size() == 2);
  const Symbol& turret_p = chassis.children[1].children[1];
  CHECK(turret_p.name == "TURRET_P");
  names.clear();
  for (const Symbol& s : turret_p.children) names.push_back(s.name + "/" + s.detail);
  CHECK(names ==
        std::vector<std::string>{"RigidBody/RigidBody", "Transform/Transform", "Light/SpotLight", "Camera/Camera"});
  REQUIRE(turret_p.children.size() == 4);
  CHECK(turret_p.children[2].kind == SymbolKind::kDevice);
  // The gun: a Transform holding a RigidBody (a mapping of types) holding a Shape.
  REQUIRE(turret_p.children[1].children.size() == 1);
  CHECK(turret_p.children[1].children[0].name == "RigidBody");
  REQUIRE(turret_p.children[1].children[0].children.size() == 1);
  CHECK(turret_p.children[1].children[0].children[0].name == "Shape");

  // A list of axis-angles: the 4th of each is in degrees (format 2.0); SpotLight's beam_width too.
  auto h = hover(d, point_of(d.text, "-90 ] ]", 0));
  REQUIRE(h);
  CHECK(h->markdown.find(fmt::format("-90° = {:.10g} rad", -kPi / 2)) != std::string::npos);
  h = hover(d, point_of(d.text, "beam_width: 36", 12));
  REQUIRE(h);
  CHECK(h->markdown.find(fmt::format("36° = {:.10g} rad", 36 * kPi / 180)) != std::string::npos);
  h = hover(d, point_of(d.text, "width: 320"));
  REQUIRE(h);
  CHECK(h->markdown.find("default: 640") != std::string::npos);  // §10.2
}

TEST_CASE("lsp features: root_link and an extra joint's link names complete and hover as links") {
  std::string text =
      "format: ChoreonoidBody\nformat_version: 2.0\nroot_link: \nlinks:\n  - name: base\n  - name: arm\n"
      "    parent: base\n";
  auto items = labels(complete(doc(text), point_of(text, "root_link: ", 11)));
  CHECK(items == std::vector<std::string>{"base", "arm"});
  text = kSmall + "  - name: finger\n    parent: hand\n";
  text.replace(text.find("link1_name: hand"), 16, "link1_name: ");
  items = labels(complete(doc(text), point_of(text, "link1_name: ", 12)));
  CHECK(items == std::vector<std::string>{"base", "arm", "hand", "finger"});

  const std::string path = kCorpus + "SR1/SR1.body";
  bodyfmt::CollectingSink sink;
  const auto model = bodyfmt::load_body(path, {}, sink);
  REQUIRE(model);
  Document d = doc(read(path), path);
  d.model = &*model;
  const auto h = hover(d, point_of(d.text, "rootLink: WAIST", 11));
  REQUIRE(h);
  CHECK(h->markdown.find("with its subtree 130.8 kg") != std::string::npos);       // Choreonoid's total mass
  CHECK(h->markdown.find("from the last text that loaded") != std::string::npos);  // not model_is_current
}

TEST_CASE("lsp features: a link's world frame is at the initial pose, joints at their initial displacement") {
  // base at z = 1; arm turns about z with joint_angle 90 (degrees, format 2.0); hand sits 1 m
  // along arm's x: at the initial pose it is at (0, 1, 1), turned 90 degrees about z.
  const std::string text =
      "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: base\n"
      "    translation: [ 0, 0, 1 ]\n    joint_type: free\n  - name: arm\n    parent: base\n"
      "    joint_type: revolute\n    joint_axis: Z\n    joint_angle: 90\n  - name: hand\n"
      "    parent: arm\n    translation: [ 1, 0, 0 ]\n";
  bodyfmt::CollectingSink sink;
  const auto model = bodyfmt::load_body_string(text, "/tmp/pose.body", {}, sink);
  REQUIRE(model);
  Document d = doc(text);
  d.model = &*model;
  d.model_is_current = true;
  const auto h = hover(d, point_of(text, "name: hand", 7));
  REQUIRE(h);
  INFO(h->markdown);
  CHECK(h->markdown.find("position [0, 1, 1] m, rotation [0, 0, 1, 90°]") != std::string::npos);
  CHECK(h->markdown.find("mass 1 kg") != std::string::npos);  // no mass data: Choreonoid's 1 kg (§6.4)
}
