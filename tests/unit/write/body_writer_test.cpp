// The canonical .body writer: what it writes loads back (through the loader, the independent
// reader here) as the same links, joints, masses, frames and shapes; the text is stable.
#include <bodyfmt/body_writer.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace bodyfmt::test {
namespace {

namespace fs = std::filesystem;

bool close(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double tolerance = 1e-12) {
  return (a - b).norm() <= tolerance * std::max({a.norm(), b.norm(), 1.0});
}
bool close(double a, double b) {
  if (a == b) return true;  // also ±kUnlimited
  return std::abs(a - b) <= 1e-12 * std::max({std::abs(a), std::abs(b), 1.0});
}

// "" when `b` has `a`'s links, joints, masses, frames and shapes (by link name), else the first difference.
std::string same_model(const Model& a, const Model& b) {
  if (a.links.size() != b.links.size()) return "link count";
  const auto frames_a = compute_world_frames(a);
  const auto frames_b = compute_world_frames(b);
  for (std::size_t i = 0; i < a.links.size(); ++i) {
    const Link& la = a.links[i];
    const LinkIndex j = b.find_link(la.name);
    if (j < 0) return la.name + " is gone";
    const Link& lb = b.links[static_cast<std::size_t>(j)];
    const std::string& n = la.name;
    if ((la.parent < 0) != (lb.parent < 0) || (la.parent >= 0 && a.links[static_cast<std::size_t>(la.parent)].name !=
                                                                     b.links[static_cast<std::size_t>(lb.parent)].name))
      return n + ": parent";
    if (la.joint_type != lb.joint_type) return n + ": joint type";
    if (la.joint_id != lb.joint_id) return n + ": joint id";
    if (la.joint_type == JointType::kRevolute || la.joint_type == JointType::kPrismatic) {
      if (!close(la.joint_axis, lb.joint_axis)) return n + ": axis";
      if (!close(la.joint_range_lower, lb.joint_range_lower) || !close(la.joint_range_upper, lb.joint_range_upper))
        return n + ": range";
      if (!close(la.velocity_lower, lb.velocity_lower) || !close(la.velocity_upper, lb.velocity_upper))
        return n + ": velocity";
      if (!close(la.effort_upper, lb.effort_upper)) return n + ": effort";
      if (!close(la.initial_displacement, lb.initial_displacement)) return n + ": displacement";
      if (!close(la.joint_axis_inertia, lb.joint_axis_inertia)) return n + ": axis inertia";
    }
    if (!close(la.X_PL.matrix(), lb.X_PL.matrix())) return n + ": X_PL";
    if (!close(frames_a[i].matrix(), frames_b[static_cast<std::size_t>(j)].matrix())) return n + ": world frame";
    const MassProperties ma = compute_mass_properties(la), mb = compute_mass_properties(lb);
    if (!close(ma.mass, mb.mass) || !close(ma.center_of_mass, mb.center_of_mass) || !close(ma.inertia, mb.inertia))
      return n + ": mass properties";
    std::vector<const Shape*> sa, sb;
    for (const Shape& s : la.shapes) sa.push_back(&s);
    for (const Shape& s : lb.shapes) sb.push_back(&s);
    if (sa.size() != sb.size()) return n + ": shape count";
    for (std::size_t k = 0; k < sa.size(); ++k) {
      if (sa[k]->geometry.index() != sb[k]->geometry.index()) return n + ": shape type";
      if (sa[k]->visual != sb[k]->visual || sa[k]->collision != sb[k]->collision) return n + ": shape part";
      if (!close(sa[k]->X_LS.matrix(), sb[k]->X_LS.matrix())) return n + ": shape placement";
      if (sa[k]->appearance.material.has_value() != sb[k]->appearance.material.has_value() ||
          (sa[k]->appearance.material && !(*sa[k]->appearance.material == *sb[k]->appearance.material)))
        return n + ": material";
    }
  }
  return "";
}

TEST_CASE("body writer: every corpus model the writer reports nothing for loads back the same") {
  const fs::path corpus = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid";
  REQUIRE(fs::exists(corpus));
  std::vector<fs::path> bodies;
  for (const auto& e : fs::recursive_directory_iterator(corpus))
    if (e.path().extension() == ".body") bodies.push_back(e.path());
  std::sort(bodies.begin(), bodies.end());
  int compared = 0, lossy = 0;
  LoadOptions options;
  options.load_meshes = false;
  for (const fs::path& body : bodies) {
    CAPTURE(body.string());
    CollectingSink sink;
    auto model = load_body(body.string(), options, sink);
    if (!model) continue;
    CollectingSink write_sink;
    const std::string text = write_body(*model, {}, write_sink);
    // Written into the model's folder (as if beside it) so that relative mesh URIs resolve the same.
    CollectingSink reload_sink;
    auto again = load_body_string(text, (body.parent_path() / "rewritten.body").string(), options, reload_sink);
    REQUIRE(again);
    for (const Diagnostic& d : reload_sink.diagnostics())
      if (d.rule_id != "load-default-mass") CHECK_MESSAGE(d.severity < Severity::kError, d.message);
    if (!write_sink.diagnostics().empty()) {
      ++lossy;  // devices, extra joints, mesh geometry: compared below only where nothing was lost
      continue;
    }
    CHECK(same_model(*model, *again) == "");
    CHECK(write_body(*again, {}, write_sink) == text);  // canonical: a second pass changes nothing
    ++compared;
  }
  MESSAGE("body writer: " << bodies.size() << " corpus bodies, " << compared << " compared, " << lossy
                          << " with something the writer does not write");
  CHECK(compared >= 5);
}

TEST_CASE("body writer: the comparison above catches each defect (mutants)") {
  CollectingSink sink;
  auto model = load_body(BODYFMT_EXAMPLES_DIR "/arm.body", LoadOptions{}, sink);
  REQUIRE(model);
  const std::string text = write_body(*model, {}, sink);
  auto again = load_body_string(text, "arm.body", LoadOptions{}, sink);
  REQUIRE(again);
  REQUIRE(same_model(*model, *again) == "");
  const Link& moving = *std::find_if(model->links.begin(), model->links.end(),
                                     [](const Link& l) { return l.joint_type == JointType::kRevolute; });
  const LinkIndex m = again->find_link(moving.name);
  auto mutant = [&](auto change) {
    Model copy = *again;
    change(copy.links[static_cast<std::size_t>(m)]);
    return same_model(*model, copy);
  };
  CHECK(mutant([](Link& l) { l.joint_range_upper += 1e-6; }) != "");
  CHECK(mutant([](Link& l) { l.velocity_upper *= 2; }) != "");
  CHECK(mutant([](Link& l) { l.joint_axis = -l.joint_axis; }) != "");
  CHECK(mutant([](Link& l) { l.X_PL.translation().x() += 1e-6; }) != "");
  CHECK(mutant([](Link& l) { l.mass_contributions.at(0).mass *= 1.001; }) != "");
  CHECK(mutant([](Link& l) { l.mass_contributions.at(0).inertia(0, 1) += 1e-6; }) != "");
  CHECK(mutant([](Link& l) { l.joint_type = JointType::kPrismatic; }) != "");
  CHECK(mutant([](Link& l) { l.joint_id += 1; }) != "");
}

TEST_CASE("body writer: numbers and strings") {
  CHECK(body_number(0.1) == "0.1");
  CHECK(body_number(-0.0) == "0");
  CHECK(body_number(1e30) == "1e+30");
  CHECK(body_number(1.0 / 3) == "0.3333333333333333");
  CHECK(body_string("LINK_1") == "LINK_1");
  CHECK(body_string("yes") == "\"yes\"");
  CHECK(body_string("1abc") == "\"1abc\"");
  CHECK(body_string("a: b") == "\"a: b\"");
  CHECK(body_string("q\"\\") == "\"q\\\"\\\\\"");
  // Each of them reads back as the same string.
  for (const std::string name : {"yes", "1abc", "a: b", "q\"\\", "tab\there", "Null"}) {
    Model model;
    model.name = name;
    model.links.emplace_back();
    model.links[0].name = name;
    CollectingSink sink;
    auto again = load_body_string(write_body(model, {}, sink), "n.body", LoadOptions{}, sink);
    REQUIRE(again);
    CHECK(again->links.at(0).name == name);
    CHECK(again->name == name);
  }
}

}  // namespace
}  // namespace bodyfmt::test
