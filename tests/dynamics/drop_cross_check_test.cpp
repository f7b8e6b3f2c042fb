// The drop cross-check (`bodysim check --cross-check mujoco`) against defective exports: each
// mutant edits body2mjcf's export of a corpus box (12.8 kg, 0.2 × 0.8 × 0.2 m) in one way before
// MuJoCo loads it, and the line that must catch it fails; exports written differently with the
// same physics pass every line. The model with a joint displaced at the start checks that both
// engines weld it there.
#include <doctest/doctest.h>

#include <bodyfmt/dynamics/drop_cross_check.h>
#include <bodyfmt/load.h>

#include <tinyxml2.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <string>

using namespace bodyfmt;
using namespace bodyfmt::dynamics;

namespace {

const std::string kBox = std::string(BODYFMT_SHARED_DIR) + "/corpus/choreonoid/misc/box1.body";

struct Loaded {
  Model model;
  Derived derived;
};

Loaded load(const std::string& path) {
  CollectingSink sink;
  std::optional<Model> model = load_body(path, LoadOptions{}, sink);
  REQUIRE(model);
  Loaded l{std::move(*model), {}};
  l.derived = compute_derived(l.model, sink);
  return l;
}

/// Edits the root <body> of the export.
using Edit = std::function<void(tinyxml2::XMLElement* root_body)>;

std::map<std::string, bool> run(const Loaded& l, const Edit& edit) {
  DropCrossCheckOptions options;
  if (edit)
    options.mutate_export = [edit](const std::filesystem::path& file, std::string& why) {
      tinyxml2::XMLDocument doc;
      if (doc.LoadFile(file.c_str()) != tinyxml2::XML_SUCCESS) {
        why = "unreadable";
        return false;
      }
      edit(doc.RootElement()->FirstChildElement("worldbody")->FirstChildElement("body"));
      return doc.SaveFile(file.c_str()) == tinyxml2::XML_SUCCESS;
    };
  CollectingSink sink;
  std::string why;
  const std::vector<CheckResult> results = run_drop_cross_check(l.model, l.derived, options, sink, why);
  INFO(why);
  REQUIRE(results.size() == 4);
  std::map<std::string, bool> passed;
  for (const char* key : {"rest height", "rest orientation", "floor force", "settle time"})
    for (const CheckResult& r : results)
      if (r.name.find(key) != std::string::npos) passed[key] = r.passed;
  REQUIRE(passed.size() == 4);
  return passed;
}

tinyxml2::XMLElement* collision_geom(tinyxml2::XMLElement* body) {
  for (tinyxml2::XMLElement* g = body->FirstChildElement("geom"); g; g = g->NextSiblingElement("geom"))
    if (g->IntAttribute("group") == 3) return g;
  FAIL("no collision geom");
  return nullptr;
}

/// body2mjcf writes a mesh that is exactly a box as a box geom; this turns the export's
/// collision box back into a mesh with the same 8 corners (an inline <mesh vertex>), as it was
/// written before, to show what MuJoCo's mesh-plane contact does with it.
bool collision_as_mesh(const std::filesystem::path& file, std::string& why) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(file.c_str()) != tinyxml2::XML_SUCCESS) {
    why = "unreadable";
    return false;
  }
  tinyxml2::XMLElement* root = doc.RootElement();
  tinyxml2::XMLElement* body = root->FirstChildElement("worldbody")->FirstChildElement("body");
  tinyxml2::XMLElement* geom = collision_geom(body);
  double h[3] = {0, 0, 0};
  if (!geom || std::string(geom->Attribute("type")) != "box" ||
      std::sscanf(geom->Attribute("size"), "%lf %lf %lf", &h[0], &h[1], &h[2]) != 3) {
    why = "the export's collision geom is no box";
    return false;
  }
  // In the order of the test models' vertex lists, which the STL had: MuJoCo 2.2.2 picks a
  // vertex's hull neighbours in the hull's order, so the contacts depend on it.
  const int signs[8][3] = {{-1, 1, 1},  {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},
                           {-1, 1, -1}, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}};
  std::string vertices;
  for (int c = 0; c < 8; ++c) {
    char corner[100];
    std::snprintf(corner, sizeof corner, "%s%.17g %.17g %.17g", c ? " " : "", signs[c][0] * h[0], signs[c][1] * h[1],
                  signs[c][2] * h[2]);
    vertices += corner;
  }
  tinyxml2::XMLElement* asset = root->FirstChildElement("asset");
  if (!asset) asset = root->InsertFirstChild(doc.NewElement("asset"))->ToElement();
  tinyxml2::XMLElement* mesh = asset->InsertNewChildElement("mesh");
  mesh->SetAttribute("name", "collision_as_mesh");
  mesh->SetAttribute("vertex", vertices.c_str());
  geom->SetAttribute("type", "mesh");
  geom->SetAttribute("mesh", "collision_as_mesh");
  geom->DeleteAttribute("size");
  return doc.SaveFile(file.c_str()) == tinyxml2::XML_SUCCESS;
}

struct Case {
  std::string name;
  Edit edit;
  std::map<std::string, bool> expected;
};

}  // namespace

TEST_CASE("drop cross-check: each defective export fails the line that must catch it and equivalent exports pass") {
  const Loaded box = load(kBox);
  const std::map<std::string, bool> all_pass = {
      {"rest height", true}, {"rest orientation", true}, {"floor force", true}, {"settle time", true}};
  auto except = [&](std::initializer_list<const char*> failing) {
    std::map<std::string, bool> m = all_pass;
    for (const char* f : failing) m[f] = false;
    return m;
  };
  const std::vector<Case> cases = {
      // Valid variants: the same physics, written differently.
      {"the export as written", nullptr, all_pass},
      {"the inertia as diaginertia instead of fullinertia",
       [](tinyxml2::XMLElement* b) {
         tinyxml2::XMLElement* in = b->FirstChildElement("inertial");
         in->DeleteAttribute("fullinertia");
         in->SetAttribute("diaginertia", "0.72533 0.08533 0.72533");
       },
       all_pass},
      {"the visual geom removed",
       [](tinyxml2::XMLElement* b) {
         for (tinyxml2::XMLElement* g = b->FirstChildElement("geom"); g; g = g->NextSiblingElement("geom"))
           if (g->IntAttribute("group") == 2) {
             b->DeleteChild(g);
             break;
           }
       },
       all_pass},
      {"a mass 0.5 % heavier (inside T8's 1 %)",
       [](tinyxml2::XMLElement* b) { b->FirstChildElement("inertial")->SetAttribute("mass", 12.8 * 1.005); }, all_pass},
      // Mutants: one defect each.
      {"a mass 2 % heavier",
       [](tinyxml2::XMLElement* b) { b->FirstChildElement("inertial")->SetAttribute("mass", 12.8 * 1.02); },
       except({"floor force"})},
      {"the collision box 1 mm taller at the bottom",
       [](tinyxml2::XMLElement* b) {
         tinyxml2::XMLElement* g = collision_geom(b);
         g->SetAttribute("size", "0.1 0.4 0.1005");
         g->SetAttribute("pos", "0 0 -0.0005");
       },
       except({"rest height"})},
      {"the collision box turned 90 degrees (standing on its end)",
       [](tinyxml2::XMLElement* b) {
         collision_geom(b)->SetAttribute("quat", "0.70710678118654757 0.70710678118654757 0 0");
       },
       except({"rest height", "settle time"})},
      // It rolls onto its side, as tall as its bottom (0.2 m): only the pose and the time show it.
      {"the centre of mass outside the box's footprint",
       [](tinyxml2::XMLElement* b) { b->FirstChildElement("inertial")->SetAttribute("pos", "0.15 0 0"); },
       except({"rest orientation", "settle time"})},
      {"the collision geom touching nothing (contype = conaffinity = 0)",
       [](tinyxml2::XMLElement* b) {
         tinyxml2::XMLElement* g = collision_geom(b);
         g->SetAttribute("contype", 0);
         g->SetAttribute("conaffinity", 0);
       },
       except({"rest height", "floor force", "settle time"})},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const std::map<std::string, bool> passed = run(box, c.edit);
    for (const auto& entry : c.expected) {
      const std::string& line = entry.first;  // named: clang 14's CAPTURE cannot take a structured binding
      const bool expected = entry.second;
      CAPTURE(line);
      const bool got = passed.at(line);
      CHECK(got == expected);
    }
  }
}

TEST_CASE("drop cross-check: a joint displaced at the start is welded there in both engines") {
  // Welded at q = 0 in MuJoCo, the leg would point down and carry the model 0.3 m higher.
  const Loaded l = load(std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/locked_displaced.body");
  DropCrossCheckOptions options;
  CollectingSink sink;
  std::string why;
  DropCrossCheckReport report;
  const std::vector<CheckResult> results = run_drop_cross_check(l.model, l.derived, options, sink, why, &report);
  INFO(why);
  REQUIRE(results.size() == 4);
  for (const CheckResult& r : results) {
    CAPTURE(r.name);
    CHECK(r.passed);
  }
  // The body rests on its own 0.1 m box: its centre 0.05 m up, less the contact's sink.
  CHECK(report.simbody.height == doctest::Approx(0.05).epsilon(0.01));
  CHECK(report.mujoco.height == doctest::Approx(0.05).epsilon(0.01));
}

TEST_CASE("drop cross-check: a fixed root is refused with a reason and nothing is simulated") {
  const Loaded arm = load(std::string(BODYFMT_EXAMPLES_DIR) + "/arm.body");
  CollectingSink sink;
  std::string why;
  CHECK(run_drop_cross_check(arm.model, arm.derived, {}, sink, why).empty());
  CHECK(why.find("free root") != std::string::npos);
}

TEST_CASE("drop cross-check: MuJoCo's mesh-plane contact skips the corner across a face narrower than 0.3·rbound") {
  // Two mesh boxes that land on an edge and tip onto a 0.16 m long face, 20 mm and 40 mm wide,
  // their collision written as a mesh in MuJoCo (body2mjcf writes a box, collision_as_mesh
  // turns it back). MuJoCo 2.2.2 adds to the deepest vertex only hull neighbours farther from it than
  // 0.3·rbound (about 30 mm for both): on the narrow face one end stands on one corner that
  // changes from step to step, the rest creeps and the orientation line fails; on the wide face
  // both corners of an end are contacts and MuJoCo rests as Simbody.
  struct Face {
    const char* file;
    double half_width;
    bool orientation_passes;
  };
  for (const Face& face : {Face{"narrow_mesh_box.body", 0.01, false}, Face{"wide_mesh_box.body", 0.02, true}}) {
    CAPTURE(face.file);
    const Loaded l = load(std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/" + face.file);
    CollectingSink sink;
    std::string why;
    DropCrossCheckReport report;
    DropCrossCheckOptions options;
    options.mutate_export = collision_as_mesh;
    const std::vector<CheckResult> results = run_drop_cross_check(l.model, l.derived, options, sink, why, &report);
    INFO(why);
    REQUIRE(results.size() == 4);
    const double skip = 0.3 * std::sqrt(0.08 * 0.08 + face.half_width * face.half_width + 0.06 * 0.06);
    CHECK(report.collision_meshes == 1);
    CHECK(report.mesh_contact_skip_max == doctest::Approx(skip).epsilon(1e-6));
    CHECK((2 * face.half_width > skip) == face.orientation_passes);
    for (const CheckResult& r : results) {
      CAPTURE(r.name);
      if (r.name.find("rest height") != std::string::npos || r.name.find("floor force") != std::string::npos)
        CHECK(r.passed);
      if (r.name.find("rest orientation") != std::string::npos) CHECK(r.passed == face.orientation_passes);
    }
    CHECK(report.simbody.turn_rate < 1e-6);
    CHECK(report.simbody.contacts_min == 4);
    CHECK(report.mujoco.contacts_max <= 3);
    if (face.orientation_passes) {
      CHECK(report.mujoco.contacts_min == 3);
      CHECK(report.mujoco.turn_rate < 1e-4);
    } else {
      CHECK(report.mujoco.contacts_min == 2);
      CHECK(report.mujoco.turn_rate > 3e-4);
    }
  }
}

TEST_CASE(
    "drop cross-check: a box that tips is compared at rest, not by when its tip ends, and as a mesh its rest creeps") {
  // The 0.16 x 0.02 x 0.12 m box lands on an edge and tips onto its 20 mm face. When a tip ends
  // is decided by the impacts, where the engines' contacts differ by design: the settle time is
  // a SKIP with that reason, and the rest is compared (height on its face, tilt, no turning).
  const Loaded l = load(std::string(BODYFMT_TEST_DATA_DIR) + "/dynamics/narrow_mesh_box.body");
  auto passed_lines = [](const std::vector<CheckResult>& results) {
    std::map<std::string, bool> passed;
    for (const char* key : {"rest height", "rest orientation", "floor force", "settle time"})
      for (const CheckResult& r : results)
        if (r.name.find(key) != std::string::npos) passed[key] = r.passed;
    return passed;
  };
  {
    CollectingSink sink;
    std::string why;
    DropCrossCheckReport report;
    const std::vector<CheckResult> results = run_drop_cross_check(l.model, l.derived, {}, sink, why, &report);
    INFO(why);
    REQUIRE(results.size() == 4);
    for (const auto& entry : passed_lines(results)) {
      const std::string& line = entry.first;
      const bool passed = entry.second;
      CAPTURE(line);
      CHECK(passed == (line != "settle time"));
    }
    const DropMeasures& sb = report.simbody;
    CHECK(report.collision_meshes == 0);  // body2mjcf wrote a box
    CHECK(sb.tipped);
    CHECK(sb.support_points == 4);
    CHECK(sb.support_span == doctest::Approx(std::hypot(0.16, 0.02)).epsilon(0.01));
    CHECK(report.impact_time == sb.support_time);
    CHECK(report.impact_time > sb.first_contact + 0.02);
    CHECK(report.relaxation_band == doctest::Approx(1e-3 * sb.support_span));
    CHECK(report.expected_settle == doctest::Approx(report.impact_time + report.mujoco_relaxation));
    // Held to the first contact plus the 0.091 s a 2 cm drop's impact needs to come within
    // 0.5 mm (the model for a flat landing), MuJoCo's settle would be more than 5 % later.
    CHECK(report.mujoco.settle_time > 1.05 * (sb.first_contact + 0.091));
    const std::string text = describe(report);
    CHECK(text.find("its last impact is the last of the 4 points it rests on") != std::string::npos);
    for (const CheckResult& r : results) {
      if (r.name.find("settle time") != std::string::npos) {
        CHECK(r.skipped);
        CHECK(r.note.find("tipped over") != std::string::npos);
      }
      if (r.name.find("rest orientation") != std::string::npos) CHECK(r.name.find("yaw left out") != std::string::npos);
    }
  }
  {
    // The same export with its collision as a mesh rocks on one corner at one end.
    DropCrossCheckOptions options;
    options.mutate_export = collision_as_mesh;
    CollectingSink sink;
    std::string why;
    DropCrossCheckReport report;
    const std::vector<CheckResult> results = run_drop_cross_check(l.model, l.derived, options, sink, why, &report);
    INFO(why);
    REQUIRE(results.size() == 4);
    CHECK(report.collision_meshes == 1);
    const std::map<std::string, bool> passed = passed_lines(results);
    // Its rest turns by itself (MuJoCo's mesh contact stands one end on one changing corner).
    CHECK_FALSE(passed.at("rest orientation"));
    CHECK(report.mujoco.turn_rate > 1e-4);
    for (const CheckResult& r : results)
      if (r.name.find("settle time") != std::string::npos) CHECK(r.skipped);
  }
  {
    // A box that lands flat has one impact: its first contact, relaxing into the height band.
    const Loaded box = load(kBox);
    CollectingSink sink;
    std::string why;
    DropCrossCheckReport report;
    REQUIRE(run_drop_cross_check(box.model, box.derived, {}, sink, why, &report).size() == 4);
    CHECK_FALSE(report.simbody.tipped);
    CHECK(report.impact_time == report.simbody.first_contact);
    CHECK(report.relaxation_band == 0.5e-3);
    CHECK(describe(report).find("lands on its rest face: its impact is its first contact") != std::string::npos);
  }
}
