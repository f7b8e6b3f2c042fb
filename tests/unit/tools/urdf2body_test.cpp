// urdf2body from the command line: URDF -> body -> URDF (body2urdf) must give the same tree,
// read back by urdfdom, with forward kinematics computed here from urdfdom's models (not from
// bodyfmt's frames); body -> URDF -> body on the corpus; exit codes and located errors.
#include "support/run_command.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

namespace bodyfmt::test {
namespace {

namespace fs = std::filesystem;

std::string quote(const fs::path& p) { return "'" + p.string() + "'"; }

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("bodyfmt_urdf2body_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A random URDF tree: every joint type urdf2body maps, random origins, axes, limits,
// inertials with rotated frames, and box, cylinder and sphere shapes with origins.
std::string random_urdf(unsigned seed, int links) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> pos(0.1, 2);
  auto v3 = [&] { return fmt::format("{} {} {}", u(rng), u(rng), u(rng)); };
  std::string out = fmt::format("<robot name=\"r{}\">\n", seed);
  for (int i = 0; i < links; ++i) {
    out += fmt::format("  <link name=\"l{}\">\n", i);
    if (i % 5 != 4) {
      const double a = pos(rng), b = pos(rng), c = pos(rng);
      // A positive-definite tensor with products of inertia: diagonal-dominant.
      out += fmt::format(
          "    <inertial><origin xyz=\"{}\" rpy=\"{}\"/><mass value=\"{}\"/>"
          "<inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/></inertial>\n",
          v3(), v3(), pos(rng), a + b, 0.1 * u(rng), 0.1 * u(rng), b + c, 0.1 * u(rng), a + c);
    }
    out += fmt::format(
        "    <visual><origin xyz=\"{}\" rpy=\"{}\"/><geometry><box size=\"{} {} {}\"/></geometry></visual>\n", v3(),
        v3(), pos(rng), pos(rng), pos(rng));
    out += fmt::format(
        "    <collision><origin xyz=\"{}\" rpy=\"{}\"/><geometry><cylinder radius=\"{}\" "
        "length=\"{}\"/></geometry></collision>\n",
        v3(), v3(), pos(rng), pos(rng));
    out += fmt::format("    <collision><geometry><sphere radius=\"{}\"/></geometry></collision>\n", pos(rng));
    out += "  </link>\n";
  }
  const char* types[] = {"revolute", "continuous", "prismatic", "fixed"};
  for (int i = 1; i < links; ++i) {
    const int parent = static_cast<int>(rng() % static_cast<unsigned>(i));
    const char* type = types[rng() % 4];
    out += fmt::format("  <joint name=\"j{}\" type=\"{}\"><parent link=\"l{}\"/><child link=\"l{}\"/>", i, type, parent,
                       i);
    out += fmt::format("<origin xyz=\"{}\" rpy=\"{}\"/><axis xyz=\"{}\"/>", v3(), v3(), v3());
    if (std::string(type) != "fixed")
      out += fmt::format("<limit lower=\"{}\" upper=\"{}\" effort=\"{}\" velocity=\"{}\"/>", -pos(rng), pos(rng),
                         10 * pos(rng), pos(rng));
    out += "</joint>\n";
  }
  return out + "</robot>\n";
}

Eigen::Isometry3d iso(const urdf::Pose& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  X.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return X;
}
Eigen::Vector3d vec(const urdf::Vector3& v) { return Eigen::Vector3d(v.x, v.y, v.z); }

bool close(double a, double b, double scale = 1.0) {
  return std::abs(a - b) <= 1e-9 * std::max({std::abs(a), std::abs(b), scale});
}
bool close(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() <= 1e-9 * std::max({a.norm(), b.norm(), 1.0});
}

// Link frames in the world from urdfdom's joints alone: X_WC = X_WP * origin * motion(q).
std::map<std::string, Eigen::Isometry3d> forward_kinematics(const urdf::ModelInterface& model,
                                                            const std::map<std::string, double>& q) {
  std::map<std::string, Eigen::Isometry3d> X_W;
  std::vector<urdf::LinkConstSharedPtr> stack{model.getRoot()};
  X_W[model.getRoot()->name] = Eigen::Isometry3d::Identity();
  while (!stack.empty()) {
    urdf::LinkConstSharedPtr link = stack.back();
    stack.pop_back();
    for (const auto& child : link->child_links) {
      const urdf::JointSharedPtr& j = child->parent_joint;
      Eigen::Isometry3d X = X_W.at(link->name) * iso(j->parent_to_joint_origin_transform);
      const Eigen::Vector3d axis = vec(j->axis).normalized();
      const double value = q.count(j->name) ? q.at(j->name) : 0.0;
      if (j->type == urdf::Joint::REVOLUTE || j->type == urdf::Joint::CONTINUOUS)
        X.rotate(Eigen::AngleAxisd(value, axis));
      else if (j->type == urdf::Joint::PRISMATIC)
        X.translate(value * axis);
      X_W[child->name] = X;
      stack.push_back(child);
    }
  }
  return X_W;
}

// The inertia in link axes: URDF's tensor is given in the inertial frame.
Eigen::Matrix3d link_inertia(const urdf::Inertial& in) {
  Eigen::Matrix3d I;
  I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  const Eigen::Matrix3d R = iso(in.origin).linear();
  return R * I * R.transpose();
}

// "" when two links' visuals (or collisions) have the same origins, types and sizes.
template <typename T>
std::string same_shapes(const std::string& name, const char* kind, const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return fmt::format("link {}: {} {} then {}", name, kind, a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    // A mesh is placed by its origin and scale together (a scale of 1 -1 -1 may come back as a
    // 180° turn with scale 1).
    auto placement = [](const auto& shape) {
      Eigen::Matrix4d X = iso(shape->origin).matrix();
      if (auto mesh = std::dynamic_pointer_cast<urdf::Mesh>(shape->geometry))
        X.topLeftCorner<3, 3>() *= vec(mesh->scale).asDiagonal();
      return X;
    };
    if (!close(placement(a[i]), placement(b[i]))) return fmt::format("link {}: {} {} placement", name, kind, i);
    const auto& ga = a[i]->geometry;
    const auto& gb = b[i]->geometry;
    if (ga->type != gb->type) return fmt::format("link {}: {} {} type", name, kind, i);
    if (auto box = std::dynamic_pointer_cast<urdf::Box>(ga)) {
      if (!close(vec(box->dim), vec(std::dynamic_pointer_cast<urdf::Box>(gb)->dim)))
        return fmt::format("link {}: box size", name);
    } else if (auto c = std::dynamic_pointer_cast<urdf::Cylinder>(ga)) {
      auto other = std::dynamic_pointer_cast<urdf::Cylinder>(gb);
      if (!close(c->radius, other->radius) || !close(c->length, other->length))
        return fmt::format("link {}: cylinder", name);
    } else if (auto s = std::dynamic_pointer_cast<urdf::Sphere>(ga)) {
      if (!close(s->radius, std::dynamic_pointer_cast<urdf::Sphere>(gb)->radius))
        return fmt::format("link {}: sphere", name);
    }
  }
  return "";
}

// "" when `b` has the same tree as `a`, else the first difference.
std::string same_tree(const urdf::ModelInterface& a, const urdf::ModelInterface& b, unsigned seed) {
  if (a.links_.size() != b.links_.size()) return fmt::format("{} links, then {}", a.links_.size(), b.links_.size());
  if (a.joints_.size() != b.joints_.size())
    return fmt::format("{} joints, then {}", a.joints_.size(), b.joints_.size());
  for (const auto& [name, la] : a.links_) {
    auto it = b.links_.find(name);
    if (it == b.links_.end()) return "link " + name + " is gone";
    const urdf::Link& lb = *it->second;
    const double ma = la->inertial ? la->inertial->mass : 0, mb = lb.inertial ? lb.inertial->mass : 0;
    if (!close(ma, mb)) return fmt::format("link {}: mass {} then {}", name, ma, mb);
    if (ma != 0) {
      if (!close(vec(la->inertial->origin.position), vec(lb.inertial->origin.position)))
        return "link " + name + ": centre of mass";
      if (!close(link_inertia(*la->inertial), link_inertia(*lb.inertial))) return "link " + name + ": inertia";
    }
    const std::string shapes = same_shapes(name, "visual", la->visual_array, lb.visual_array) +
                               same_shapes(name, "collision", la->collision_array, lb.collision_array);
    if (!shapes.empty()) return shapes;
  }
  std::mt19937 rng(seed);
  for (const auto& [name, ja] : a.joints_) {
    auto it = b.joints_.find(name);
    if (it == b.joints_.end()) return "joint " + name + " is gone";
    const urdf::Joint& jb = *it->second;
    if (ja->type != jb.type) return fmt::format("joint {}: type {} then {}", name, ja->type, jb.type);
    if (ja->parent_link_name != jb.parent_link_name || ja->child_link_name != jb.child_link_name)
      return "joint " + name + ": parent or child";
    if (!close(iso(ja->parent_to_joint_origin_transform).matrix(), iso(jb.parent_to_joint_origin_transform).matrix()))
      return "joint " + name + ": origin";
    if (ja->type == urdf::Joint::FIXED) continue;
    if (!close(vec(ja->axis).normalized(), vec(jb.axis).normalized())) return "joint " + name + ": axis";
    if (ja->type != urdf::Joint::CONTINUOUS && ja->type != urdf::Joint::FLOATING &&
        (!ja->limits || !jb.limits || !close(ja->limits->lower, jb.limits->lower) ||
         !close(ja->limits->upper, jb.limits->upper)))
      return "joint " + name + ": range";
    // A continuous joint without <limit> comes back with body2urdf's stand-in 1e30 (no limit).
    const double va = ja->limits ? ja->limits->velocity : 1e30, ea = ja->limits ? ja->limits->effort : 1e30;
    const double vb = jb.limits ? jb.limits->velocity : 1e30, eb = jb.limits ? jb.limits->effort : 1e30;
    if (!close(va, vb) || !close(ea, eb)) return "joint " + name + ": velocity or effort";
  }
  // Forward kinematics at 100 random configurations within the limits.
  for (int k = 0; k < 100; ++k) {
    std::map<std::string, double> q;
    for (const auto& [name, j] : a.joints_) {
      if (!j->limits) continue;
      const double lo = j->type == urdf::Joint::CONTINUOUS ? -kPi : j->limits->lower;
      const double hi = j->type == urdf::Joint::CONTINUOUS ? kPi : j->limits->upper;
      q[name] = std::uniform_real_distribution<double>(std::min(lo, hi), std::max(lo, hi))(rng);  // lower > upper too
    }
    const auto fa = forward_kinematics(a, q);
    const auto fb = forward_kinematics(b, q);
    for (const auto& [name, X] : fa) {
      const Eigen::Isometry3d& Y = fb.at(name);
      if ((X.translation() - Y.translation()).norm() > 1e-9 || (X.linear() - Y.linear()).norm() > 1e-9)
        return fmt::format("link {}: frame differs at configuration {} by {} m", name, k,
                           (X.translation() - Y.translation()).norm());
    }
  }
  return "";
}

TEST_CASE("urdf2body: URDF -> body -> URDF keeps the tree, the inertias and forward kinematics") {
  const fs::path dir = scratch("round_trip");
  int compared = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    CAPTURE(seed);
    const std::string text = random_urdf(seed, 3 + static_cast<int>(seed % 17));
    std::ofstream(dir / "in.urdf") << text;
    const CommandResult import = run_command(std::string(BODYFMT_URDF2BODY) + " in.urdf -o in.body", dir.string());
    REQUIRE_MESSAGE(import.status == 0, import.output);
    const CommandResult exported = run_command(std::string(BODYFMT_BODY2URDF) + " in.body -o out.urdf", dir.string());
    REQUIRE_MESSAGE(exported.status <= 1, exported.output);
    auto a = urdf::parseURDF(text);
    auto b = urdf::parseURDF(read(dir / "out.urdf"));
    REQUIRE(a);
    REQUIRE(b);
    CHECK(same_tree(*a, *b, seed) == "");
    ++compared;
  }
  CHECK(compared == 20);
  fs::remove_all(dir);
}

TEST_CASE("urdf2body: the round-trip comparison catches each defect (mutants)") {
  // One defect per mutant in the re-exported URDF; same_tree must name each.
  const std::string base = random_urdf(7, 6);
  auto original = urdf::parseURDF(base);
  REQUIRE(original);
  CHECK(same_tree(*original, *original, 7) == "");
  // {where (searched from the end), what, replacement}: each changes one value of one element.
  const std::vector<std::tuple<std::string, std::string, std::string>> mutants = {
      {"<inertial>", "<mass value=\"", "<mass value=\"1"},                  // a mass
      {"<inertial>", "<inertia ixx=\"", "<inertia ixx=\"1"},                // an inertia
      {"<inertial>", "<origin xyz=\"", "<origin xyz=\"1"},                  // a centre of mass
      {"type=\"continuous\"", "type=\"continuous\"", "type=\"revolute\""},  // a joint type
      {"type=\"continuous\"", "<axis xyz=\"", "<axis xyz=\"1"},             // an axis (changes FK)
      {"type=\"prismatic\"", "<limit lower=\"", "<limit lower=\"-1"},       // a range
      {"type=\"prismatic\"", "velocity=\"", "velocity=\"1"},                // a velocity limit
      {"<joint", "<origin xyz=\"", "<origin xyz=\"1"},                      // a joint origin
      {"<box size=\"", "<box size=\"", "<box size=\"2"},                    // a box size
      {"<collision><origin", "<origin xyz=\"", "<origin xyz=\"1"},          // a collision origin (a cylinder)
      {"<sphere radius=\"", "<sphere radius=\"", "<sphere radius=\"3"},     // a sphere
  };
  for (const auto& mutant : mutants) {
    // Named copies: clang 14 cannot capture structured bindings in CAPTURE's lambda.
    const std::string& where = std::get<0>(mutant);
    const std::string& from = std::get<1>(mutant);
    const std::string& to = std::get<2>(mutant);
    CAPTURE(where);
    CAPTURE(from);
    std::string text = base;
    const std::size_t anchor = text.rfind(where);
    REQUIRE(anchor != std::string::npos);
    const std::size_t at = text.find(from, anchor);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
    auto mutated = urdf::parseURDF(text);
    if (!mutated) continue;  // urdfdom refuses it: nothing to compare
    CHECK(same_tree(*original, *mutated, 7) != "");
  }
}

TEST_CASE("urdf2body: exit codes, standard output, --strict and --allow-loss, located errors") {
  const fs::path dir = scratch("cli");
  const std::string tool = BODYFMT_URDF2BODY;
  std::ofstream(dir / "mimic.urdf")
      << "<robot name=\"m\">\n  <link name=\"a\"/><link name=\"b\"/>\n"
         "  <joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>\n"
         "    <mimic joint=\"x\"/></joint>\n</robot>\n";
  std::ofstream(dir / "broken.urdf") << "<robot name=\"m\">\n  <link name=\"a\">\n</robot>\n";
  std::ofstream(dir / "orphan.urdf")
      << "<robot name=\"m\">\n  <link name=\"a\"/>\n"
         "  <joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"zz\"/></joint>\n"
         "</robot>\n";
  CHECK(run_command(tool + " --help", dir.string()).status == 0);
  CHECK(run_command(tool + " --version", dir.string()).output.find("urdf2body ") == 0);
  CHECK(run_command(tool + " mimic.urdf", dir.string()).status == 2);  // -o is required

  CommandResult lossy = run_command(tool + " mimic.urdf -o m.body", dir.string());
  CHECK(lossy.status == 1);
  CHECK(lossy.output.find("mimic.urdf:4:5: warning:") != std::string::npos);
  CHECK(fs::exists(dir / "m.body"));
  CHECK(run_command(tool + " mimic.urdf -o m2.body --allow-loss joints", dir.string()).status == 0);
  CommandResult strict = run_command(tool + " mimic.urdf -o m3.body --strict", dir.string());
  CHECK(strict.status == 2);
  CHECK_FALSE(fs::exists(dir / "m3.body"));
  CommandResult to_stdout = run_command(tool + " mimic.urdf -o - --allow-loss joints", dir.string(), false);
  CHECK(to_stdout.status == 0);
  CHECK(to_stdout.output == read(dir / "m.body"));
  CommandResult from_stdin = run_command(tool + " - -o - --allow-loss joints < mimic.urdf", dir.string(), false);
  CHECK(from_stdin.status == 0);

  CommandResult broken = run_command(tool + " broken.urdf -o b.body", dir.string());
  CHECK(broken.status == 2);
  // tinyxml2 reports a mismatched end tag at the start of the element left open (line 2).
  CHECK(broken.output.find("broken.urdf:2:") != std::string::npos);
  CHECK(broken.output.find("[import-syntax]") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "b.body"));
  CommandResult orphan = run_command(tool + " orphan.urdf -o o.body", dir.string());
  CHECK(orphan.status == 2);
  CHECK(orphan.output.find("orphan.urdf:3:57: error:") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "o.body"));
  // The URDF is an input: never written over.
  CHECK(run_command(tool + " mimic.urdf -o mimic.urdf", dir.string()).status == 2);
  CHECK(read(dir / "mimic.urdf").find("<robot") == 0);
  // --best-effort lets the strict loss be written: the refused write is the reason, not --strict.
  CommandResult refused = run_command(tool + " mimic.urdf -o mimic.urdf --strict --best-effort", dir.string());
  CHECK(refused.status == 2);
  CHECK(refused.output.find("[export-write]") != std::string::npos);
  CHECK(refused.output.find("--strict makes every loss") == std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("urdf2body: --copy-meshes copies each mesh once beside the body, the body refers to the copies") {
  const fs::path dir = scratch("copy");
  fs::create_directories(dir / "pkg/meshes");
  fs::create_directories(dir / "pkg/urdf");
  fs::create_directories(dir / "out");
  std::ofstream(dir / "pkg/package.xml") << "<package><name>pkg</name></package>\n";
  const std::string stl =
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid t\n";
  std::ofstream(dir / "pkg/meshes/part.stl") << stl;
  std::ofstream(dir / "pkg/urdf/r.urdf")
      << "<robot name=\"r\"><link name=\"a\">"
         "<visual><geometry><mesh filename=\"package://pkg/meshes/part.stl\"/></geometry></visual>"
         "<collision><geometry><mesh filename=\"../meshes/part.stl\" scale=\"2 2 2\"/></geometry></collision>"
         "</link></robot>\n";
  const CommandResult r =
      run_command(std::string(BODYFMT_URDF2BODY) + " pkg/urdf/r.urdf -o out/r.body --copy-meshes", dir.string());
  REQUIRE_MESSAGE(r.status == 0, r.output);
  CHECK(read(dir / "out/meshes/r/part.stl") == stl);
  const std::string body = read(dir / "out/r.body");
  CHECK(body.find("uri: \"meshes/r/part.stl\"") != std::string::npos);
  CHECK(body.find("part_2") == std::string::npos);  // one copy for both references
  CollectingSink sink;
  auto model = load_body((dir / "out/r.body").string(), LoadOptions{}, sink);
  REQUIRE(model);
  REQUIRE(model->links.at(0).shapes.size() == 2);
  CHECK(geometry_get<MeshResource>(model->links[0].shapes[0].geometry).resolved_path ==
        fs::weakly_canonical(dir / "out/meshes/r/part.stl").string());
  CHECK_FALSE(model->meshes.empty());
  // A source mesh where its copy would go is never written over; nothing is written.
  fs::create_directories(dir / "self/meshes/r");
  std::ofstream(dir / "self/meshes/r/part.stl") << "solid other\nendsolid other\n";
  std::ofstream(dir / "self/r.urdf")
      << "<robot name=\"r\"><link name=\"a\"><visual><geometry><mesh filename=\"meshes/r/part.stl\"/>"
         "</geometry></visual></link></robot>\n";
  CHECK(
      run_command(std::string(BODYFMT_URDF2BODY) + " r.urdf -o r.body --copy-meshes", (dir / "self").string()).status ==
      2);
  CHECK(read(dir / "self/meshes/r/part.stl") == "solid other\nendsolid other\n");
  CHECK_FALSE(fs::exists(dir / "self/r.body"));
  fs::remove_all(dir);
}

TEST_CASE("urdf2body: the output loads without warnings and is byte-identical run to run") {
  const fs::path dir = scratch("load");
  std::ofstream(dir / "r.urdf") << random_urdf(3, 12);
  REQUIRE(run_command(std::string(BODYFMT_URDF2BODY) + " r.urdf -o a.body", dir.string()).status == 0);
  REQUIRE(run_command(std::string(BODYFMT_URDF2BODY) + " r.urdf -o b.body", dir.string()).status == 0);
  CHECK(read(dir / "a.body") == read(dir / "b.body"));
  CollectingSink sink;
  auto model = load_body((dir / "a.body").string(), LoadOptions{}, sink);
  REQUIRE(model);
  for (const Diagnostic& d : sink.diagnostics()) CHECK_MESSAGE(d.severity < Severity::kWarning, d.message);
  CHECK(model->links.size() == 12);
  fs::remove_all(dir);
}

// The conventions outside the URDF spec that issue 37 names, as the harness below counts them:
// found in the text with tinyxml2 (not by the importer), so that the count does not come from
// the code under test.
struct Conventions {
  bool world_root = false;        // a root link named 'world'
  bool inertia_defaults = false;  // an <inertia> without ixy, ixz or iyz
  bool multi_shape = false;       // a <geometry> with more than one shape
  bool reversed_limits = false;   // a <limit> with lower > upper
  bool zero_radius = false;       // a sphere, cylinder or capsule of radius 0
  bool capsule = false;           // a <capsule>
};

// Every element below `e`, depth first.
template <typename F>
void each_element(const tinyxml2::XMLElement* e, const F& f) {
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    f(c);
    each_element(c, f);
  }
}

Conventions find_conventions(const std::string& text) {
  Conventions k;
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) return k;
  std::set<std::string> children;
  bool world = false;
  each_element(doc.RootElement(), [&](const tinyxml2::XMLElement* e) {
    const std::string name = e->Name();
    if (name == "child" && e->Attribute("link")) children.insert(e->Attribute("link"));
    if (name == "link" && e->Attribute("name", "world")) world = true;
    if (name == "inertia" && (!e->Attribute("ixy") || !e->Attribute("ixz") || !e->Attribute("iyz")))
      k.inertia_defaults = true;
    if (name == "geometry" && e->FirstChildElement() && e->FirstChildElement()->NextSiblingElement())
      k.multi_shape = true;
    if (name == "limit" && e->Attribute("lower") && e->Attribute("upper") &&
        e->DoubleAttribute("lower") > e->DoubleAttribute("upper"))
      k.reversed_limits = true;
    if ((name == "sphere" || name == "cylinder" || name == "capsule") && e->Attribute("radius") &&
        e->DoubleAttribute("radius", 1) == 0)
      k.zero_radius = true;
    if (name == "capsule") k.capsule = true;
  });
  k.world_root = world && !children.count("world");
  return k;
}

// What urdfdom must read to compare: missing products of inertia written as 0 (urdfdom refuses
// them; Drake and MuJoCo read 0) and capsules as cylinders of the same radius and length
// (urdfdom knows no capsule). Applied alike to the original and to the export.
std::string for_urdfdom(const std::string& text) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) return text;
  std::vector<tinyxml2::XMLElement*> all;
  each_element(doc.RootElement(),
               [&](const tinyxml2::XMLElement* e) { all.push_back(const_cast<tinyxml2::XMLElement*>(e)); });
  for (tinyxml2::XMLElement* e : all) {
    if (std::strcmp(e->Name(), "inertia") == 0)
      for (const char* a : {"ixy", "ixz", "iyz"})
        if (!e->Attribute(a)) e->SetAttribute(a, "0");
    if (std::strcmp(e->Name(), "capsule") == 0) e->SetName("cylinder");
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

// The first line of `output` that names `what` ("" when none does).
std::string first_line_with(const std::string& output, const std::string& what) {
  std::stringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    if (line.find(what) != std::string::npos) return line;
  return "";
}

// Public URDF collections (not part of the project): BODYFMT_URDF_COLLECTIONS=DIR:DIR... runs
// every URDF under them through urdf2body, bodycheck and body2urdf, and the round-trip
// comparison above (on the text urdfdom reads, for_urdfdom); prints one outcome per file (the
// same tree, or refused or reported at a line with the reason) and, per collection, the counts
// per convention of issue 37. BODYFMT_URDF_TOOLS=DIR takes urdf2body, bodycheck and body2urdf
// from DIR instead of this build (to count an older build the same way). Without the variable
// it says so and checks nothing.
TEST_CASE("urdf2body: public URDF collections (BODYFMT_URDF_COLLECTIONS)") {
  const char* collections = std::getenv("BODYFMT_URDF_COLLECTIONS");
  if (!collections || !*collections) {
    MESSAGE("not run: set BODYFMT_URDF_COLLECTIONS to folders of URDF files");
    return;
  }
  const char* tools = std::getenv("BODYFMT_URDF_TOOLS");
  auto tool = [&](const char* built, const char* name) {
    return tools && *tools ? quote(fs::path(tools) / name) : std::string(built);
  };
  const std::string urdf2body = tool(BODYFMT_URDF2BODY, "urdf2body");
  const std::string bodycheck = tool(BODYFMT_BODYCHECK, "bodycheck");
  const std::string body2urdf = tool(BODYFMT_BODY2URDF, "body2urdf");
  const fs::path dir = scratch("collections");
  std::stringstream list(collections);
  for (std::string root; std::getline(list, root, ':');) {
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(root))
      if (e.path().extension() == ".urdf") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    const char* kinds[] = {"world root",      "inertia defaults", "multi-shape",
                           "reversed limits", "zero radius",      "capsule"};
    std::map<std::string, std::pair<int, int>> per_kind;  // files of the kind, of them the same tree
    int same = 0, reported = 0, refused = 0, unread = 0, other = 0;
    std::map<std::string, int> refusals;  // by rule
    for (const fs::path& file : files) {
      const std::string text = read(file);
      const Conventions k = find_conventions(text);
      const bool has[] = {k.world_root, k.inertia_defaults, k.multi_shape, k.reversed_limits, k.zero_radius, k.capsule};
      std::string outcome;
      const std::string name = fs::relative(file, root).string();
      const CommandResult import = run_command(urdf2body + " " + quote(file) + " -o m.body", dir.string());
      auto original = urdf::parseURDF(for_urdfdom(text));
      if (import.status > 1) {
        const std::string line = first_line_with(import.output, ": error:") + first_line_with(import.output, "fatal");
        std::string rule = line.substr(line.rfind('[') == std::string::npos ? line.size() : line.rfind('['));
        ++refused;
        ++refusals[rule.empty() ? "(no located error)" : rule];
        outcome = "refused: " + (line.empty() ? import.output.substr(0, 200) : line.substr(line.find(':') + 1));
      } else if (!original) {  // urdfdom's own negative tests (a bad version, conflicting materials)
        ++unread;
        outcome = "imported; urdfdom refuses the original, so there is nothing to compare";
      } else if (run_command(bodycheck + " -q --no-config m.body", dir.string()).status > 1) {
        ++other;
        outcome = "bodycheck cannot read the import";
      } else {
        const CommandResult back =
            run_command(body2urdf + " -q m.body -o m.urdf" + (k.capsule ? " --capsules" : ""), dir.string());
        auto again = urdf::parseURDF(for_urdfdom(read(dir / "m.urdf")));
        const std::string problem = back.status > 1 ? "body2urdf exit " + std::to_string(back.status) + ": " +
                                                          first_line_with(back.output, "error")
                                    : !again ? "urdfdom cannot read the export"
                                             : same_tree(*original, *again, 1);
        if (problem.empty()) {
          ++same;
          outcome = "same tree";
          for (int i = 0; i < 6; ++i)
            if (has[i]) ++per_kind[kinds[i]].second;
        } else {
          const std::string loss = first_line_with(import.output, "[export-loss]");
          if (!loss.empty())
            ++reported;
          else
            ++other;
          outcome = "differs (" + problem + ")" +
                    (loss.empty() ? "; urdf2body reported no loss"
                                  : "; urdf2body's first loss: " + loss.substr(loss.find(':') + 1));
        }
      }
      std::string tags;
      for (int i = 0; i < 6; ++i)
        if (has[i]) {
          ++per_kind[kinds[i]].first;
          tags += std::string(tags.empty() ? " [" : ", ") + kinds[i];
        }
      if (!tags.empty()) tags += "]";
      MESSAGE(name << tags << ": " << outcome);
    }
    std::string kind_counts;
    for (const char* kind : kinds)
      kind_counts += fmt::format("; {} {}/{}", kind, per_kind[kind].second, per_kind[kind].first);
    std::string refusal_counts;
    for (const auto& [rule, n] : refusals) refusal_counts += fmt::format(" {} {}", rule, n);
    MESSAGE(root << ": " << files.size() << " URDF: " << same << " the same tree, " << reported
                 << " differ where urdf2body reported a loss (not necessarily the cause), " << refused
                 << " refused at a line (" << refusal_counts << " ), " << unread << " that urdfdom refuses, " << other
                 << " other" << kind_counts << " (same tree/files)");
  }
  fs::remove_all(dir);
}

// Issue 37's conventions through both tools: a 'world' root on a fixed joint (its name and
// origin), an <inertia> without products, a reversed range and a capsule come back from
// body2urdf as they came in (compared on the text urdfdom reads, for_urdfdom).
TEST_CASE("urdf2body: a world root and the simulators' conventions come back from body2urdf") {
  const fs::path dir = scratch("conventions");
  const std::string text = R"(<robot name="c">
  <link name="world"/>
  <joint name="bolt" type="fixed"><parent link="world"/><child link="base"/>
    <origin xyz="0.5 -1 2" rpy="0.1 0.2 0.3"/></joint>
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="1" iyy="2" izz="2.5"/></inertial>
    <collision><origin xyz="0 0 0.25"/><geometry><capsule radius="0.1" length="0.5"/></geometry></collision>
  </link>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="0.5" upper="-0.5" effort="3" velocity="2"/></joint>
</robot>
)";
  std::ofstream(dir / "in.urdf") << text;
  const CommandResult import = run_command(std::string(BODYFMT_URDF2BODY) + " in.urdf -o in.body", dir.string());
  REQUIRE_MESSAGE(import.status == 0, import.output);  // warnings only
  CHECK(import.output.find("[import-convention]") != std::string::npos);
  const CommandResult back =
      run_command(std::string(BODYFMT_BODY2URDF) + " in.body --capsules -o out.urdf", dir.string());
  REQUIRE_MESSAGE(back.status <= 1, back.output);
  auto a = urdf::parseURDF(for_urdfdom(text));
  auto b = urdf::parseURDF(for_urdfdom(read(dir / "out.urdf")));
  REQUIRE(a);
  REQUIRE(b);
  CHECK(same_tree(*a, *b, 37) == "");
  CHECK(read(dir / "out.urdf").find("<capsule") != std::string::npos);
  fs::remove_all(dir);
}

// Choreonoid ships SR1 in both formats. The imported SR1.urdf must have SR1.body's links, joint
// ids, masses, centres of mass, inertias and frames at 100 random configurations. The URDF itself
// differs from the body where the test says so.
TEST_CASE("urdf2body: Choreonoid's SR1.urdf against its SR1.body") {
  const fs::path sr1 = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid" / "SR1";
  REQUIRE(fs::exists(sr1 / "SR1.urdf"));
  const fs::path dir = scratch("sr1");
  const CommandResult import =
      run_command(std::string(BODYFMT_URDF2BODY) + " " + quote(sr1 / "SR1.urdf") + " -o SR1.body", dir.string());
  // The URDF's visuals name materials 'Appearance2' ... that it never defines (urdfdom warns too).
  CHECK(import.status == 0);
  CHECK(import.output.find("[import-material]") != std::string::npos);
  CollectingSink sink_a, sink_b;
  auto body = load_body((sr1 / "SR1.body").string(), LoadOptions{}, sink_a);
  auto imported = load_body((dir / "SR1.body").string(), LoadOptions{}, sink_b);
  REQUIRE(body);
  REQUIRE(imported);
  REQUIRE(imported->links.size() == body->links.size());
  std::vector<LinkIndex> to_imported;
  for (const Link& a : body->links) {
    CAPTURE(a.name);
    const LinkIndex j = imported->find_link(a.name);
    REQUIRE(j >= 0);
    to_imported.push_back(j);
    const Link& b = imported->links[static_cast<std::size_t>(j)];
    CHECK(a.joint_type == b.joint_type);
    CHECK(a.joint_id == b.joint_id);
    const MassProperties ma = compute_mass_properties(a), mb = compute_mass_properties(b);
    CHECK(close(ma.mass, mb.mass));
    CHECK(close(ma.center_of_mass, mb.center_of_mass));
    CHECK(close(ma.inertia, mb.inertia));
    if (a.joint_type != JointType::kRevolute) continue;
    // SR1.urdf rounds ±90° and ±180° to ±1.57 and ±3.14 rad...
    CHECK(std::abs(a.joint_range_lower - b.joint_range_lower) < 0.0016);
    CHECK(std::abs(a.joint_range_upper - b.joint_range_upper) < 0.0016);
    // ...and gives every joint a velocity limit (10 rad/s; 0 for RARM_ELBOW) where the body has none.
    CHECK(a.velocity_upper == kUnlimited);
    CHECK((b.velocity_upper == 10 || (a.name == "RARM_ELBOW" && b.velocity_upper == 0)));
  }
  // The cameras and sensors (with the camera shapes on CHEST) are not in SR1.urdf.
  CHECK(body->devices.size() == 7);
  CHECK(imported->devices.empty());
  // SR1.body places its free root WAIST 0.7135 m up; a URDF has no initial pose, so frames are
  // compared relative to the root.
  CHECK(body->links[0].X_PL.translation() == Eigen::Vector3d(0, 0, 0.7135));
  CHECK(imported->links[0].X_PL.translation() == Eigen::Vector3d::Zero());
  std::mt19937 rng(27);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int k = 0; k < 100; ++k) {
    std::vector<double> q(body->links.size()), q_imported(imported->links.size());
    for (std::size_t i = 0; i < q.size(); ++i) q_imported[static_cast<std::size_t>(to_imported[i])] = q[i] = angle(rng);
    const auto fa = compute_root_relative_frames(*body, q);
    const auto fb = compute_root_relative_frames(*imported, q_imported);
    for (std::size_t i = 0; i < q.size(); ++i) {
      CAPTURE(body->links[i].name);
      const Eigen::Isometry3d& b = fb[static_cast<std::size_t>(to_imported[i])];
      REQUIRE((fa[i].translation() - b.translation()).norm() <= 1e-9);
      REQUIRE((fa[i].linear() - b.linear()).norm() <= 1e-9);
    }
  }
  fs::remove_all(dir);
}

// body -> URDF (--floating-base, so that the root's joint and pose are kept) -> body: links,
// masses and frames as the corpus model had them, for every model whose export reported no loss.
TEST_CASE("urdf2body: body -> URDF -> body on the corpus") {
  const fs::path corpus = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid";
  if (!fs::exists(corpus)) {
    FAIL_CHECK("the shared corpus is missing");
    return;
  }
  const fs::path dir = scratch("corpus");
  int exported = 0, lossless = 0, compared = 0;
  std::vector<fs::path> bodies;
  for (const auto& e : fs::recursive_directory_iterator(corpus))
    if (e.path().extension() == ".body") bodies.push_back(e.path());
  std::sort(bodies.begin(), bodies.end());
  for (const fs::path& body : bodies) {
    CAPTURE(body.string());
    CollectingSink original_sink;
    auto original = load_body(body.string(), LoadOptions{}, original_sink);
    if (!original) continue;
    const CommandResult to_urdf = run_command(
        std::string(BODYFMT_BODY2URDF) + " " + quote(body) + " --floating-base --copy-meshes -o m.urdf", dir.string());
    if (to_urdf.status == 2) continue;
    ++exported;
    if (to_urdf.output.find("[export-loss]") != std::string::npos) continue;
    ++lossless;
    const CommandResult back = run_command(std::string(BODYFMT_URDF2BODY) + " m.urdf -o m.body", dir.string());
    REQUIRE_MESSAGE(back.status == 0, back.output);
    CollectingSink sink;
    auto again = load_body((dir / "m.body").string(), LoadOptions{}, sink);
    REQUIRE(again);
    REQUIRE(again->links.size() == original->links.size());
    const auto frames_a = compute_world_frames(*original);
    const auto frames_b = compute_world_frames(*again);
    for (std::size_t i = 0; i < original->links.size(); ++i) {
      const Link& la = original->links[i];
      const LinkIndex j = again->find_link(la.name);
      REQUIRE_MESSAGE(j >= 0, la.name);
      const Link& lb = again->links[static_cast<std::size_t>(j)];
      CHECK(lb.joint_type == la.joint_type);
      CHECK((la.parent < 0 ? std::string() : original->links[static_cast<std::size_t>(la.parent)].name) ==
            (lb.parent < 0 ? std::string() : again->links[static_cast<std::size_t>(lb.parent)].name));
      const MassProperties ma = compute_mass_properties(la), mb = compute_mass_properties(lb);
      CHECK(close(ma.mass, mb.mass));
      CHECK(close(ma.center_of_mass, mb.center_of_mass));
      CHECK(close(ma.inertia, mb.inertia));
      CHECK(close(frames_a[i].matrix(), frames_b[static_cast<std::size_t>(j)].matrix()));
    }
    ++compared;
  }
  MESSAGE("corpus: " << bodies.size() << " bodies, " << exported << " exported, " << lossless << " without losses, "
                     << compared << " compared after the round trip");
  CHECK(compared > 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace bodyfmt::test
