// Links read while the file is parsed (LoadOptions::stream_links, body_reader.cpp's LinkStream)
// against the same file read from its whole YAML tree: the model, every finding and every
// source location must be the same, including the files where streaming has to give up
// (a header key after `links`, `links` written twice, a SubBody, a YAML resource).

#include "support/load_helpers.h"

#include <bodyfmt/fix.h>

#include <filesystem>
#include <sstream>

using namespace bodyfmt;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

namespace {

struct Loaded {
  std::optional<Model> model;
  std::vector<Diagnostic> diagnostics;
};

Loaded load_with(const std::string& text, bool stream, LoadOptions options = {}) {
  options.stream_links = stream;
  CollectingSink sink;
  Loaded result;
  result.model = load_body_string(text, "/virtual/streamed.body", options, sink);
  result.diagnostics = sink.diagnostics();
  return result;
}

std::string describe(const SourceLocation& at) {
  return at.file.str() + ":" + std::to_string(at.line) + ":" + std::to_string(at.column);
}

std::string describe(const Diagnostic& d) {
  std::ostringstream out;
  out << describe(d.location) << " " << severity_name(d.severity) << " [" << d.rule_id << "] " << d.message;
  if (d.via) out << " via " << describe(*d.via);
  for (const FixIt& fix : d.fixes) out << " fix " << fix.begin << "-" << fix.end << "=" << fix.replacement;
  return out.str();
}

// Every location a link keeps, in link order.
std::vector<std::string> link_locations(const Model& model) {
  std::vector<std::string> result;
  for (const Link& link : model.links) {
    const LinkSources& s = link.sources;
    for (const SourceLocation& at : {link.source, s.name(), s.parent(), s.translation(), s.rotation(), s.joint_type(),
                                     s.joint_axis(), s.joint_id(), s.joint_range(), s.mass(), s.inertia()})
      result.push_back(link.name + " " + describe(at));
    for (const Shape& shape : link.shapes) result.push_back(link.name + " shape " + describe(shape.source));
  }
  return result;
}

/// Checks that streaming and the whole tree give the same result; returns the streamed one.
Loaded check_same(const std::string& text, const LoadOptions& options = {}) {
  const Loaded streamed = load_with(text, true, options);
  const Loaded whole = load_with(text, false, options);
  REQUIRE(streamed.model.has_value() == whole.model.has_value());
  REQUIRE(streamed.diagnostics.size() == whole.diagnostics.size());
  for (std::size_t i = 0; i < whole.diagnostics.size(); ++i)
    CHECK(describe(streamed.diagnostics[i]) == describe(whole.diagnostics[i]));
  if (whole.model) {
    const std::optional<std::string> difference = model_difference(*streamed.model, *whole.model, 0);
    CHECK_MESSAGE(!difference, difference.value_or(""));
    CHECK(link_locations(*streamed.model) == link_locations(*whole.model));
  }
  return streamed;
}

std::vector<std::string> link_names(const Model& model) {
  std::vector<std::string> names;
  for (const Link& link : model.links) names.push_back(link.name);
  return names;
}

}  // namespace

TEST_CASE("link stream: every corpus model loads the same as from the whole tree") {
  const std::filesystem::path corpus = BODYFMT_SHARED_DIR "/corpus/choreonoid";
  REQUIRE(std::filesystem::is_directory(corpus));
  LoadOptions options;
  options.load_meshes = false;  // imported after the links, from the model: the same either way
  int files = 0;
  for (const auto& item : std::filesystem::recursive_directory_iterator(corpus)) {
    if (!item.is_regular_file() || item.path().extension() != ".body") continue;
    CAPTURE(item.path().string());
    options.stream_links = true;
    CollectingSink streamed_sink, whole_sink;
    const auto streamed = load_body(item.path().string(), options, streamed_sink);
    options.stream_links = false;
    const auto whole = load_body(item.path().string(), options, whole_sink);
    REQUIRE(streamed.has_value() == whole.has_value());
    REQUIRE(streamed_sink.diagnostics().size() == whole_sink.diagnostics().size());
    for (std::size_t i = 0; i < whole_sink.diagnostics().size(); ++i)
      CHECK(describe(streamed_sink.diagnostics()[i]) == describe(whole_sink.diagnostics()[i]));
    if (whole) {
      const std::optional<std::string> difference = model_difference(*streamed, *whole, 0);
      CHECK_MESSAGE(!difference, difference.value_or(""));
      CHECK(link_locations(*streamed) == link_locations(*whole));
    }
    ++files;
  }
  CHECK(files >= 50);
}

TEST_CASE("link stream: angle_unit written after links is applied to every link") {
  // Choreonoid reads the header first, wherever it is: the 1 of joint_range is 1 radian.
  const Loaded r = check_same(R"(format: ChoreonoidBody
format_version: 1.0
links:
  - {name: A, joint_type: free}
  - {name: B, parent: A, joint_type: revolute, joint_id: 0, joint_range: [-1, 1]}
angle_unit: radian
)");
  REQUIRE(r.model);
  CHECK(r.model->links[1].joint_range_upper == 1.0);
  CHECK_FALSE(r.model->angles_in_degrees);

  // The same with the unit before the links takes the streamed path and gives the same value.
  const Loaded before = check_same(R"(format: ChoreonoidBody
format_version: 1.0
angle_unit: radian
links:
  - {name: A, joint_type: free}
  - {name: B, parent: A, joint_type: revolute, joint_id: 0, joint_range: [-1, 1]}
)");
  REQUIRE(before.model);
  CHECK(before.model->links[1].joint_range_upper == 1.0);
}

TEST_CASE("link stream: angle_unit radian before links and degree after: the last one wins") {
  // The streamed links are read in radians; the whole header says degrees (the last key wins),
  // so they must be read again in degrees, and the format note must not call the file radian.
  const Loaded r = check_same(R"(format: ChoreonoidBody
format_version: 1.0
angle_unit: radian
links:
  - {name: A, joint_type: free}
  - {name: B, parent: A, joint_type: revolute, joint_id: 0, joint_range: [-90, 90]}
angle_unit: degree
)");
  REQUIRE(r.model);
  CHECK(r.model->angles_in_degrees);
  CHECK(r.model->links[1].joint_range_upper == doctest::Approx(M_PI / 2));
}

TEST_CASE("link stream: format_version after links decides the format") {
  // Without format_version before links, the links are read once the whole header is known.
  const Loaded r = check_same(R"(format: ChoreonoidBody
links:
  - {name: A, joint_type: free, jointType: fixed}
format_version: 1.0
)");
  REQUIRE(r.model);
  CHECK(r.model->format_version == 1.0);
}

TEST_CASE("link stream: links written twice: the last one is the model") {
  const Loaded r = check_same(R"(format: ChoreonoidBody
format_version: 2.0
links:
  - {name: FIRST}
links:
  - {name: SECOND}
  - {name: THIRD, parent: SECOND}
)");
  REQUIRE(r.model);
  CHECK(link_names(*r.model) == std::vector<std::string>{"SECOND", "THIRD"});
  REQUIRE(r.diagnostics.size() >= 1);
  CHECK(r.diagnostics.front().rule_id == "yaml-duplicate-key");
}

TEST_CASE("link stream: an anchor inside one link is used by a later link") {
  const Loaded r = check_same(R"(format: ChoreonoidBody
format_version: 2.0
links:
  - {name: A, joint_type: free, mass: 1, inertia: &I [1, 0, 0, 0, 1, 0, 0, 0, 1]}
  - {name: B, parent: A, mass: 2, inertia: *I, translation: [0, 0, "x"]}
  - {name: C, parent: B, mass: 2, inertia: *I}
)");
  REQUIRE(r.model);
  REQUIRE(r.model->links.size() == 3);
  CHECK(r.model->links[2].mass_contributions.at(0).inertia(1, 1) == 1.0);
  // The bad translation of B is reported at its value, while B is read during the parse.
  bool found = false;
  for (const Diagnostic& d : r.diagnostics)
    if (d.location.line == 5 && d.location.column == 68) found = true;
  CHECK(found);
}

TEST_CASE("link stream: links after a SubBody keep their order, and its findings are reported once") {
  LoadOptions options;
  const std::string sub = std::filesystem::weakly_canonical("/virtual/sub.body").string();
  options.file_texts[sub] = "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - {name: S0, bogus_key: 1}\n";
  const std::string links = R"(links:
  - {name: A, joint_type: free}
  - {type: SubBody, uri: sub.body, parent: A}
  - {name: B, parent: S0}
  - {name: C, parent: A}
)";
  // The unit before the links: read during the parse. After them: read again from the tree,
  // when the sub-body is already in the load's cache.
  for (const std::string& text : {"format: ChoreonoidBody\nformat_version: 1.0\nangle_unit: radian\n" + links,
                                  "format: ChoreonoidBody\nformat_version: 1.0\n" + links + "angle_unit: radian\n"}) {
    CAPTURE(text);
    const Loaded r = check_same(text, options);
    REQUIRE(r.model);
    CHECK(link_names(*r.model) == std::vector<std::string>{"A", "S0", "B", "C"});
    int info_keys = 0;
    for (const Diagnostic& d : r.diagnostics) info_keys += d.location.file == sub && d.rule_id == "load-info-key";
    CHECK(info_keys == 1);
  }
}

TEST_CASE("link stream: a YAML resource sees an anchor written after the links") {
  LoadOptions options;
  const std::string library = std::filesystem::weakly_canonical("/virtual/library.yaml").string();
  options.file_texts[library] = "shapes:\n  - {type: Shape, geometry: *late}\n";
  const Loaded r = check_same(R"(format: ChoreonoidBody
format_version: 2.0
links:
  - name: A
    joint_type: free
    elements:
      - {type: Resource, uri: library.yaml, node: shapes}
geometries:
  box: &late {type: Box, size: [1, 2, 3]}
)",
                              options);
  REQUIRE(r.model);
  for (const Diagnostic& d : r.diagnostics) CHECK_MESSAGE(d.rule_id != "yaml-undefined-alias", describe(d));
}

TEST_CASE("link stream: a file that does not parse reports only the YAML error") {
  const Loaded r = check_same(R"(format: ChoreonoidBody
format_version: 2.0
links:
  - {name: A, joint_type: free, bogus: 1}
  - {name: B, parent: A}
extra: [unclosed
)");
  CHECK_FALSE(r.model);
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].rule_id == "yaml-syntax");
}

TEST_CASE("link stream: a refused header leaves the links unread") {
  const Loaded r = check_same(R"(format: ChoreonoidBody
format_version: 7.0
links:
  - {name: A, joint_type: free, bogus: 1}
)");
  CHECK_FALSE(r.model);
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].rule_id == "load-format-version");
}

TEST_CASE("link stream: the node budget counts the links read during the parse") {
  // The root, two header values and the sequence are 4 nodes; each link 2 more: 12 in all.
  const std::string text = R"(format: ChoreonoidBody
format_version: 2.0
links:
  - {name: A}
  - {name: B}
  - {name: C}
  - {name: D}
)";
  LoadOptions options;
  options.max_expanded_yaml_nodes = 8;
  Loaded r = check_same(text, options);
  CHECK_FALSE(r.model);
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].rule_id == "yaml-alias-expansion");
  CHECK(pos(r.diagnostics[0]) == Pos{6, 5});  // the link C
  options.max_expanded_yaml_nodes = 11;       // links taken during the parse still count
  CHECK_FALSE(check_same(text, options).model);
  options.max_expanded_yaml_nodes = 12;
  CHECK(check_same(text, options).model);
}
