// Loader unit tests for load/wrapper_reader.cpp: wrapper body files (body-format-spec §2.4).
// The model files are stand-in texts (LoadOptions::file_texts) under a folder that does not
// exist, so nothing is read from disk.

#include "support/load_helpers.h"

#include <map>

using namespace bodyfmt;
using bodyfmt::test::LoadResult;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

namespace {

const char* const kInner = R"(format: ChoreonoidBody
format_version: 2.0
links:
  - name: BASE
    joint_type: free
    mass: 2
    inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]
    elements:
      - {type: Shape, geometry: {type: Cylinder, radius: 0.1, height: 0.2}}
      - {type: Shape, geometry: {type: Sphere, radius: 0.1, division_number: 8}}
  - name: ARM
    parent: BASE
    joint_type: revolute
    joint_id: 0
    mass: 1
    inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]
)";

LoadResult load_wrapper(std::string_view text, LoadOptions options = {},
                        std::map<std::string, std::string> files = {{"/wrapped/inner.body", kInner}}) {
  for (auto& [path, content] : files) options.file_texts[path] = content;
  CollectingSink sink;
  LoadResult result;
  result.model =
      load_body_string(std::string(text.substr(text.front() == '\n' ? 1 : 0)), "/wrapped/w.body", options, sink);
  result.diagnostics = sink.diagnostics();
  return result;
}

}  // namespace

TEST_CASE("wrapper: a .body model file is the model, named after the wrapper") {
  auto r = load_wrapper(R"(
model_file: inner.body
)");
  REQUIRE(r.m().links.size() == 2);
  CHECK(r.m().name == "w");
  CHECK(r.m().source_file == "/wrapped/w.body");
  CHECK(r.link("ARM").source.file.str() == "/wrapped/inner.body");
  r.expect_clean();
}

TEST_CASE("wrapper: the model file's own name wins") {
  std::string named = kInner;
  named.insert(named.find("links:"), "name: Inner\n");
  auto r = load_wrapper("model_file: inner.body\n", {}, {{"/wrapped/inner.body", named}});
  CHECK(r.m().name == "Inner");
}

TEST_CASE("wrapper: geometry divisionNumber sets the primitives that give none") {
  auto r = load_wrapper(R"(
model_file: inner.body
geometry: {divisionNumber: 12}
)");
  const Link& base = r.link("BASE");
  REQUIRE(base.shapes.size() == 2);
  CHECK(base.shapes[0].division_number == 12);
  CHECK(base.shapes[1].division_number == 8);  // its own
  r.expect_clean();
}

TEST_CASE("wrapper: geometry must be a mapping, divisionNumber a number") {
  auto r = load_wrapper("model_file: inner.body\ngeometry: 12\n");
  CHECK_FALSE(r.model);
  CHECK(pos(r.take("load-wrapper")) == Pos{2, 11});
  auto n = load_wrapper("model_file: inner.body\ngeometry: {divisionNumber: many}\n");
  CHECK_FALSE(n.model);
  CHECK(n.has("load-number"));
}

TEST_CASE("wrapper: linkInfo for a missing link, property keys and simulator keys") {
  auto r = load_wrapper(R"(
model_file: inner.body
linkInfo:
  ARM: {drive_stiffness: 100, mass: 5}
  BASSE: {drive_damping: 1}
  BASE: 3
)");
  REQUIRE(r.model);
  const Diagnostic missing = r.take("wrapper-link-info");
  CHECK(pos(missing) == Pos{4, 3});
  CHECK(missing.fix_hint.find("\"BASE\"") != std::string::npos);
  CHECK(pos(r.take("load-ignored-key")) == Pos{3, 31});
  CHECK(pos(r.take("load-ignored-value")) == Pos{5, 9});
  CHECK(pos(r.take("load-info-key")) == Pos{3, 9});
  CHECK(r.link("ARM").mass_contributions.front().mass == 1);  // not 5
  r.expect_clean();
}

TEST_CASE("wrapper: keys of a body file and typos in a wrapper") {
  auto r = load_wrapper(R"(
model_file: inner.body
links: []
link_info: {ARM: {a: 1}}
)");
  REQUIRE(r.model);
  CHECK(pos(r.take("load-ignored-key")) == Pos{2, 1});
  CHECK(pos(r.take("load-unknown-key")) == Pos{3, 1});
  r.expect_clean();
}

TEST_CASE("wrapper: formats without a reader are located errors at model_file") {
  for (const char* file : {"robot.urdf", "robot.wrl", "robot.xacro", "robot.sdf", "robot", "robot.URDF"}) {
    CAPTURE(file);
    auto r = load_wrapper(std::string("name: x\nmodel_file: ") + file + "\n");
    CHECK_FALSE(r.model);
    CHECK(pos(r.take("wrapper-format")) == Pos{2, 13});
  }
}

TEST_CASE("wrapper: a reader installed for the extension reads the file") {
  LoadOptions options;
  std::string seen_path, seen_text;
  options.model_file_readers[".urdf"] = [&](const std::string& path, const std::string& text, const LoadOptions&,
                                            DiagnosticSink&) {
    seen_path = path;
    seen_text = text;
    Model model;
    model.name = "robot";
    Link link;
    link.name = "ROOT";
    Shape shape;
    shape.geometry = Box{Eigen::Vector3d(1, 1, 1)};
    link.shapes.push_back(shape);
    model.links.push_back(link);
    return std::optional<Model>(std::move(model));
  };
  auto r = load_wrapper("model_file: sub/../robot.urdf\ngeometry: {divisionNumber: 30}\n", options,
                        {{"/wrapped/robot.urdf", "<robot/>"}});
  CHECK(seen_path == "/wrapped/robot.urdf");
  CHECK(seen_text == "<robot/>");
  CHECK(r.m().name == "w");
  CHECK(r.link("ROOT").shapes.front().division_number == 30);
  r.expect_clean();
}

TEST_CASE("wrapper: a wrapper naming itself or a cycle of wrappers") {
  auto self = load_wrapper("model_file: w.body\n", {}, {{"/wrapped/w.body", "model_file: w.body\n"}});
  CHECK_FALSE(self.model);
  CHECK(pos(self.take("wrapper-recursion")) == Pos{1, 13});
  auto cycle = load_wrapper("model_file: a.body\n", {},
                            {{"/wrapped/a.body", "model_file: b.body\n"}, {"/wrapped/b.body", "modelFile: a.body\n"}});
  CHECK_FALSE(cycle.model);
  const Diagnostic inner = cycle.take("wrapper-recursion");
  CHECK(inner.location.file.str() == "/wrapped/b.body");
  CHECK(inner.message.find("w.body -> a.body -> b.body -> a.body") != std::string::npos);
}

TEST_CASE("wrapper: a model file that cannot be read") {
  auto r = load_wrapper("model_file: nowhere.body\n", {}, {});
  CHECK_FALSE(r.model);
  CHECK(pos(r.take("wrapper-missing")) == Pos{1, 13});
  auto uri = load_wrapper("model_file: package://robot/robot.urdf\n");
  CHECK_FALSE(uri.model);
  CHECK(pos(uri.take("wrapper-format")) == Pos{1, 13});
}

TEST_CASE("wrapper: a chain of wrappers deeper than 64 levels is refused, not followed to the end of the stack") {
  std::map<std::string, std::string> files;
  for (int i = 0; i < 200; ++i)
    files["/wrapped/w" + std::to_string(i) + ".body"] = "model_file: w" + std::to_string(i + 1) + ".body\n";
  files["/wrapped/w200.body"] = kInner;
  auto r = load_wrapper("model_file: w0.body\n", {}, files);
  CHECK_FALSE(r.model);
  const Diagnostic deep = r.take("wrapper-recursion");
  CHECK(deep.location.file.str() == "/wrapped/w62.body");
  CHECK(pos(deep) == Pos{1, 13});
  auto shallow = load_wrapper("model_file: w190.body\n", {}, files);
  CHECK(shallow.m().links.size() == 2);
}
