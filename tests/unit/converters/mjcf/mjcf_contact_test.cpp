// body2mjcf's contacts, checked in MuJoCo 2.2.2: with self-collision off (the default, as in
// Choreonoid) no model touches itself anywhere in its joint ranges, and it still lands on a
// floor and touches another export in the same scene; --self-collision keeps MuJoCo's rule
// (the same sweep then finds self-contacts, which shows the sweep can see them).
#include "mjcf_writer.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <fmt/format.h>
#include <mujoco/mujoco.h>
#include "support/export_helpers.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using namespace bodyfmt;
using bodyfmt::mjcf::MjcfOptions;

namespace {

using bodyfmt::test::fresh_dir;
using bodyfmt::test::read;

const fs::path kCorpus = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid";

/// Writes the MJCF of `model` (loaded from `body`, a file or YAML text) to `xml`; false when
/// the model does not load cleanly or the export fails.
bool write(const std::string& body, bool is_text, const fs::path& xml, const MjcfOptions& options) {
  CollectingSink sink;
  std::optional<Model> model =
      is_text ? load_body_string(body, "generated.body", LoadOptions{}, sink) : load_body(body, LoadOptions{}, sink);
  for (const Diagnostic& d : sink.diagnostics())
    if (d.severity >= Severity::kError) return false;
  if (!model) return false;
  const Derived derived = compute_derived(*model, sink);
  converters::OutputSet output(xml);
  return mjcf::write_mjcf(*model, derived, options, output, sink) && output.commit(sink);
}

struct Scene {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  std::string error;
  explicit Scene(const fs::path& xml) {
    char err[1000] = "";
    m = mj_loadXML(xml.string().c_str(), nullptr, err, sizeof err);
    error = err;
    if (m) d = mj_makeData(m);
  }
  ~Scene() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
};

/// A scene that includes the given exports (in its folder) and, with `floor`, a default plane.
fs::path scene(const fs::path& dir, const std::vector<std::string>& includes, bool floor) {
  const fs::path path = dir / "scene.xml";
  std::ofstream out(path);
  out << "<mujoco model=\"scene\">\n";
  for (const std::string& file : includes) out << "  <include file=\"" << file << "\"/>\n";
  if (floor) out << "  <worldbody><geom name=\"floor\" type=\"plane\" size=\"0 0 1\"/></worldbody>\n";
  out << "</mujoco>\n";
  return path;
}

/// Contacts at the current state between geoms for which `counts` holds.
template <class Pred>
int contacts(const mjModel* m, const mjData* d, Pred counts) {
  int n = 0;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& k = d->contact[c];
    n += counts(m->geom_bodyid[k.geom1], m->geom_bodyid[k.geom2], k.geom1, k.geom2) ? 1 : 0;
  }
  return n;
}

/// Drives every hinge and slide joint through its range: each joint alone at both bounds, then
/// random configurations within the ranges (±π, ±0.2 m where unlimited); free joints stay at
/// qpos0. Returns how many of the configurations had a contact between bodies for which
/// `counts` holds (any contact without it).
int configurations_with_contact(const mjModel* m, mjData* d, int random_configurations = 100,
                                const std::function<bool(int, int)>& counts = {}) {
  std::vector<std::pair<double, double>> range(static_cast<std::size_t>(m->njnt));
  for (int j = 0; j < m->njnt; ++j) {
    const bool hinge = m->jnt_type[j] == mjJNT_HINGE;
    range[static_cast<std::size_t>(j)] = m->jnt_limited[j]
                                             ? std::make_pair(m->jnt_range[2 * j], m->jnt_range[2 * j + 1])
                                             : std::make_pair(hinge ? -M_PI : -0.2, hinge ? M_PI : 0.2);
  }
  auto moving = [&](int j) { return m->jnt_type[j] == mjJNT_HINGE || m->jnt_type[j] == mjJNT_SLIDE; };
  int touching = 0;
  auto probe = [&] {
    mj_forward(m, d);
    bool touched = false;
    for (int c = 0; c < d->ncon; ++c)
      touched = touched || !counts || counts(m->geom_bodyid[d->contact[c].geom1], m->geom_bodyid[d->contact[c].geom2]);
    touching += touched ? 1 : 0;
  };
  mju_copy(d->qpos, m->qpos0, m->nq);
  probe();
  for (int j = 0; j < m->njnt; ++j) {
    if (!moving(j)) continue;
    for (double q : {range[static_cast<std::size_t>(j)].first, range[static_cast<std::size_t>(j)].second}) {
      mju_copy(d->qpos, m->qpos0, m->nq);
      d->qpos[m->jnt_qposadr[j]] = q;
      probe();
    }
  }
  std::mt19937 rng(25);
  for (int r = 0; r < random_configurations; ++r) {
    mju_copy(d->qpos, m->qpos0, m->nq);
    for (int j = 0; j < m->njnt; ++j) {
      if (!moving(j)) continue;
      std::uniform_real_distribution<double> u(range[static_cast<std::size_t>(j)].first,
                                               range[static_cast<std::size_t>(j)].second);
      d->qpos[m->jnt_qposadr[j]] = u(rng);
    }
    probe();
  }
  return touching;
}

/// A model of overlapping boxes: a root box and `arms` boxes on revolute joints about Z, all
/// through the origin, so that every pair of links touches at every angle. Links are named
/// PREFIX_ROOT, PREFIX_1, ...; the root is free or fixed at `x`.
std::string boxes(const std::string& name, const std::string& prefix, int arms, bool free, double x, double z) {
  std::string s = fmt::format(
      "format: ChoreonoidBody\nformat_version: 2.0\nangle_unit: degree\nname: {0}\nlinks:\n"
      "  - name: {1}_ROOT\n    joint_type: {2}\n    translation: [{3}, 0, {4}]\n    mass: 1\n"
      "    inertia: [0.01, 0, 0, 0.01, 0, 0.01]\n    elements:\n      - type: Shape\n"
      "        geometry: {{ type: Box, size: [0.1, 0.1, 0.1] }}\n",
      name, prefix, free ? "free" : "fixed", x, z);
  for (int i = 1; i <= arms; ++i)
    s += fmt::format(
        "  - name: {0}_{1}\n    parent: {0}_ROOT\n    joint_type: revolute\n    joint_axis: Z\n"
        "    joint_range: [-180, 180]\n    rotation: [0, 0, 1, {2}]\n    mass: 0.1\n"
        "    inertia: [0.001, 0, 0, 0.001, 0, 0.001]\n    elements:\n      - type: Shape\n"
        "        translation: [0.1, 0, 0]\n        geometry: {{ type: Box, size: [0.3, 0.04, 0.04] }}\n",
        prefix, i, 360.0 * i / arms);
  return s;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("mjcf contact: no corpus model touches itself anywhere in its joint ranges unless --self-collision") {
  REQUIRE(fs::exists(kCorpus));
  std::vector<fs::path> bodies;
  for (const auto& e : fs::recursive_directory_iterator(kCorpus))
    if (e.path().extension() == ".body") bodies.push_back(e.path());
  std::sort(bodies.begin(), bodies.end());
  const fs::path dir = fresh_dir("mjcf_self_collision");
  int swept = 0, self_touching = 0;
  for (const fs::path& body : bodies) {
    const std::string name = fs::relative(body, kCorpus).string();
    CAPTURE(name);
    MjcfOptions options;
    options.balance_inertia = true;
    if (!write(body.string(), false, dir / "off.xml", options)) continue;  // models Choreonoid refuses
    options.collision_group = 9;
    REQUIRE(write(body.string(), false, dir / "group.xml", options));
    options.collision_group = 0;
    options.self_collision = true;
    REQUIRE(write(body.string(), false, dir / "on.xml", options));
    for (const char* file : {"off.xml", "group.xml"}) {
      CAPTURE(file);
      Scene s(dir / file);
      INFO(s.error);
      REQUIRE(s.m != nullptr);
      const int touching = configurations_with_contact(s.m, s.d);
      CHECK(touching == 0);
    }
    Scene on(dir / "on.xml");
    REQUIRE(on.m != nullptr);
    self_touching += configurations_with_contact(on.m, on.d) > 0 ? 1 : 0;
    ++swept;
  }
  MESSAGE("swept " << swept << " models; with --self-collision " << self_touching << " of them touch themselves");
  CHECK(swept >= 48);
  // GR001, JACO2, Labo1, Labo1v2, PA10, 2F-85, UR5-2F85, pendulum and pyramid touch themselves
  // at q = 0 alone; more do somewhere in their ranges.
  CHECK(self_touching >= 9);
  fs::remove_all(dir);
}

TEST_CASE("mjcf contact: the exclude scheme for small models, contact bits beyond 64 colliding bodies") {
  const fs::path dir = fresh_dir("mjcf_contact_schemes");
  MjcfOptions options;
  // Small: one <exclude> per pair of colliding bodies, MuJoCo's default contact bits.
  REQUIRE(write(boxes("Small", "S", 5, true, 0, 1), true, dir / "small.xml", options));
  const std::string small = read(dir / "small.xml");
  CHECK(count(small, "<exclude ") == 15);                              // 6 bodies
  CHECK(count(small, "contype=\"") == count(small, "contype=\"0\""));  // visual geoms only
  // Large: no excludes; every collision geom in the group derived from the model name.
  REQUIRE(write(boxes("Large", "L", 64, true, 0, 1), true, dir / "large.xml", options));
  const std::string large = read(dir / "large.xml");
  const int group = mjcf::collision_group_of("Large");
  REQUIRE(group >= 1);
  REQUIRE(group <= mjcf::kMaxCollisionGroup);
  CHECK(count(large, "<exclude ") == 0);
  CHECK(count(large, fmt::format("contype=\"{}\"", 1u << group)) == 65);
  // Buffers for every collision geom on a floor: 4 contacts each, 4 rows per contact and a row
  // per joint limit, never below MuJoCo's defaults; rows held to 2e6 / nv.
  CHECK(count(small, "<size nconmax=\"100\" njmax=\"500\"/>") == 1);
  CHECK(count(large, "<size nconmax=\"260\" njmax=\"1104\"/>") == 1);
  REQUIRE(write(boxes("Huge", "H", 1100, true, 0, 1), true, dir / "huge.xml", options));
  const std::string huge = read(dir / "huge.xml");
  CHECK(count(huge, "<size nconmax=\"4404\" njmax=\"1808\"/>") == 1);  // nv = 1106
  CHECK(count(huge, "buffers capped: 4404 contacts and 18716 constraint rows") == 1);
  // An explicit group is used even for a small model.
  options.collision_group = 4;
  REQUIRE(write(boxes("Small", "S", 5, true, 0, 1), true, dir / "small4.xml", options));
  CHECK(count(read(dir / "small4.xml"), "contype=\"16\" conaffinity=\"2147483631\"") == 6);
  // Every arm overlaps every other at every angle: MuJoCo finds contacts only when asked to.
  for (const char* file : {"small.xml", "large.xml", "small4.xml"}) {
    CAPTURE(file);
    Scene s(dir / file);
    INFO(s.error);
    REQUIRE(s.m != nullptr);
    CHECK(configurations_with_contact(s.m, s.d, 20) == 0);
  }
  options = {};
  options.self_collision = true;
  for (int arms : {5, 64}) {
    CAPTURE(arms);
    REQUIRE(write(boxes("On", "O", arms, true, 0, 1), true, dir / "on.xml", options));
    const std::string on = read(dir / "on.xml");
    CHECK(count(on, "<exclude ") == 0);
    CHECK(count(on, "contype=\"") == arms + 1);  // only the visual geoms' contype="0"
    Scene s(dir / "on.xml");
    REQUIRE(s.m != nullptr);
    CHECK(configurations_with_contact(s.m, s.d, 20) == 1 + 2 * arms + 20);
  }
  fs::remove_all(dir);
}

TEST_CASE("mjcf contact: an export lands on a default floor, with excludes and with contact bits") {
  const fs::path dir = fresh_dir("mjcf_contact_floor");
  struct Case {
    std::string body;
    bool is_text;
    int group;
  };
  const std::vector<Case> cases = {{(kCorpus / "GR001" / "GR001.body").string(), false, 0},
                                   {(kCorpus / "GR001" / "GR001.body").string(), false, 30},
                                   {boxes("Small", "S", 5, true, 0, 0.5), true, 0},
                                   {boxes("Large", "L", 80, true, 0, 0.5), true, 0}};
  for (const Case& c : cases) {
    CAPTURE(c.body.substr(0, 60));
    CAPTURE(c.group);
    MjcfOptions options;
    options.balance_inertia = true;
    options.collision_group = c.group;
    REQUIRE(write(c.body, c.is_text, dir / "model.xml", options));
    Scene s(scene(dir, {"model.xml"}, true));
    INFO(s.error);
    REQUIRE(s.m != nullptr);
    const int floor = mj_name2id(s.m, mjOBJ_GEOM, "floor");
    REQUIRE(floor >= 0);
    int with_floor = 0, others = 0;
    for (int step = 0; step < 2000; ++step) {  // 2 s
      mj_step(s.m, s.d);
      with_floor = contacts(s.m, s.d, [&](int, int, int g1, int g2) { return g1 == floor || g2 == floor; });
      others += contacts(s.m, s.d, [&](int, int, int g1, int g2) { return g1 != floor && g2 != floor; });
    }
    CHECK(with_floor > 0);
    CHECK(others == 0);
    // It rests on the floor instead of falling through it.
    double lowest = INFINITY;
    for (int b = 1; b < s.m->nbody; ++b) lowest = std::min(lowest, s.d->xpos[3 * b + 2]);
    CHECK(lowest > -0.05);
    for (int i = 0; i < s.m->nv; ++i) REQUIRE(std::isfinite(s.d->qvel[i]));
  }
  fs::remove_all(dir);
}

TEST_CASE("mjcf contact: two exports in one scene touch each other but not themselves") {
  const fs::path dir = fresh_dir("mjcf_contact_two");
  struct Case {
    int arms_a, group_a, arms_b, group_b;
    bool touch;
  };
  // Excludes with excludes, a group with excludes, two groups, and two exports in one group
  // (documented: they do not touch; give each its own --collision-group).
  const std::vector<Case> cases = {
      {4, 0, 6, 0, true}, {70, 0, 4, 0, true}, {4, 3, 4, 0, true}, {4, 3, 4, 5, true}, {4, 3, 4, 3, false}};
  for (const Case& c : cases) {
    CAPTURE(c.arms_a);
    CAPTURE(c.group_a);
    CAPTURE(c.arms_b);
    CAPTURE(c.group_b);
    MjcfOptions options;
    options.collision_group = c.group_a;
    // Fixed roots 0.15 m apart: the arms of one sweep through the other's.
    REQUIRE(write(boxes("RobotA", "A", c.arms_a, false, 0, 0), true, dir / "a.xml", options));
    options.collision_group = c.group_b;
    REQUIRE(write(boxes("RobotB", "B", c.arms_b, false, 0.15, 0), true, dir / "b.xml", options));
    Scene s(scene(dir, {"a.xml", "b.xml"}, false));
    INFO(s.error);
    REQUIRE(s.m != nullptr);
    auto robot = [&](int body) { return std::string(mj_id2name(s.m, mjOBJ_BODY, body)).substr(0, 1); };
    const int between =
        configurations_with_contact(s.m, s.d, 50, [&](int b1, int b2) { return robot(b1) != robot(b2); });
    const int within =
        configurations_with_contact(s.m, s.d, 50, [&](int b1, int b2) { return robot(b1) == robot(b2); });
    CHECK(within == 0);
    CHECK((between > 0) == c.touch);
  }
  fs::remove_all(dir);
}

TEST_CASE("mjcf contact: every corpus model lands on a floor without filling MuJoCo's buffers (<size>)") {
  REQUIRE(fs::exists(kCorpus));
  std::vector<fs::path> bodies;
  for (const auto& e : fs::recursive_directory_iterator(kCorpus))
    if (e.path().extension() == ".body") bodies.push_back(e.path());
  std::sort(bodies.begin(), bodies.end());
  const fs::path dir = fresh_dir("mjcf_contact_buffers");
  int landed = 0, peak_contacts = 0, peak_rows = 0;
  for (const fs::path& body : bodies) {
    const std::string name = fs::relative(body, kCorpus).string();
    CAPTURE(name);
    MjcfOptions options;
    options.balance_inertia = true;
    if (!write(body.string(), false, dir / "model.xml", options)) continue;  // models Choreonoid refuses
    Scene s(scene(dir, {"model.xml"}, true));
    INFO(s.error);
    REQUIRE(s.m != nullptr);
    for (int step = 0; step < 1500; ++step) {  // 1.5 s: every free model is down by then
      mj_step(s.m, s.d);
      peak_contacts = std::max(peak_contacts, s.d->ncon);
      peak_rows = std::max(peak_rows, s.d->nefc);
    }
    for (int w = 0; w < mjNWARNING; ++w) {
      CAPTURE(w);
      CHECK(s.d->warning[w].number == 0);
    }
    ++landed;
  }
  MESSAGE("landed " << landed << " models; at most " << peak_contacts << " contacts and " << peak_rows
                    << " constraint rows at once");
  CHECK(landed >= 48);
  // MuJoCo's defaults (100 contacts, 500 rows) would not hold them: 2F-85 makes 288 and 1,170.
  CHECK(peak_contacts > 100);
  CHECK(peak_rows > 500);
  fs::remove_all(dir);
}
