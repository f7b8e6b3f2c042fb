// body2urdf: the writer against urdfdom and check_urdf, the corpus, losses, output, SR1.
#include "urdf_writer.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>
#include "support/export_helpers.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using namespace bodyfmt;
using bodyfmt::converters::OutputSet;
using bodyfmt::urdf::UrdfOptions;

namespace {

using bodyfmt::test::fresh_dir;
using bodyfmt::test::marked_lines;
using bodyfmt::test::read;
using bodyfmt::test::reported_lines;

const fs::path kData = fs::path(BODYFMT_TEST_DATA_DIR) / "urdf";
const fs::path kCorpus = fs::path(BODYFMT_SHARED_DIR) / "corpus" / "choreonoid";

std::vector<fs::path> corpus_bodies() {
  std::vector<fs::path> out;
  if (!fs::exists(kCorpus)) return out;
  for (const auto& e : fs::recursive_directory_iterator(kCorpus)) {
    if (e.path().extension() == ".body") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct Export {
  std::optional<Model> model;
  Derived derived;
  std::map<std::string, std::string> files;
  std::string urdf;
  std::vector<Diagnostic> diagnostics;  // from the writer only
  bool ok = false;
};

Export export_file(const fs::path& body, const UrdfOptions& options = {}, const fs::path& out = "out/model.urdf") {
  Export e;
  CollectingSink load_sink;
  e.model = load_body(body.string(), LoadOptions{}, load_sink);
  if (!e.model) return e;
  e.derived = compute_derived(*e.model, load_sink);
  OutputSet output(out);
  CollectingSink sink;
  e.ok = bodyfmt::urdf::write_urdf(*e.model, e.derived, options, output, sink);
  e.files = output.files();
  e.urdf = e.files[out.filename().string()];
  e.diagnostics = sink.diagnostics();
  return e;
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string quote(const fs::path& p) { return "'" + p.string() + "'"; }

Eigen::Isometry3d iso(const ::urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  X.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).toRotationMatrix();
  return X;
}

Eigen::Vector3d vec(const ::urdf::Vector3& v) { return {v.x, v.y, v.z}; }

bool close(double a, double b, double tol = 1e-9) { return std::abs(a - b) <= tol * std::max(1.0, std::abs(b)); }

double max_abs_diff(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::max((a.translation() - b.translation()).cwiseAbs().maxCoeff(),
                  (a.linear() - b.linear()).cwiseAbs().maxCoeff());
}

double stand_in(double v) {
  return v >= kUnlimited ? bodyfmt::urdf::kUnlimitedStandIn : v <= -kUnlimited ? -bodyfmt::urdf::kUnlimitedStandIn : v;
}

/// Compares one export with the model it came from; returns the first problem or "".
std::string round_trip_problem(const Model& model, const Derived& derived, const ::urdf::ModelInterface& u) {
  std::ostringstream why;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    auto ul = u.getLink(link.name);
    if (!ul) return "link " + link.name + " missing";
    if (!ul->inertial) return "link " + link.name + ": no inertial";
    const MassProperties& mp = derived.mass[i];
    const Eigen::Isometry3d X_LC = iso(ul->inertial->origin);
    const auto& in = *ul->inertial;
    Eigen::Matrix3d Ic;
    Ic << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    const Eigen::Matrix3d I = X_LC.linear() * Ic * X_LC.linear().transpose();  // rotated back
    const Eigen::Matrix3d want = 0.5 * (mp.inertia + mp.inertia.transpose());
    if (!close(in.mass, mp.mass)) return "link " + link.name + ": mass";
    if ((X_LC.translation() - mp.center_of_mass).cwiseAbs().maxCoeff() > 1e-9) return "link " + link.name + ": CoM";
    if ((I - want).cwiseAbs().maxCoeff() > 1e-9 * std::max(1.0, want.cwiseAbs().maxCoeff())) {
      return "link " + link.name + ": inertia";
    }
    if (i == 0) continue;
    auto uj = ul->parent_joint;
    if (!uj) return "link " + link.name + ": no joint";
    if (uj->parent_link_name != model.links[static_cast<std::size_t>(link.parent)].name)
      return "joint parent of " + link.name;
    if (max_abs_diff(iso(uj->parent_to_joint_origin_transform), Eigen::Isometry3d(link.X_PL.matrix())) > 1e-9)
      return "joint origin of " + link.name;
    const bool revolute = link.joint_type == JointType::kRevolute, prismatic = link.joint_type == JointType::kPrismatic;
    if (revolute || prismatic) {
      if ((vec(uj->axis) - link.joint_axis.normalized()).cwiseAbs().maxCoeff() > 1e-9)
        return "joint axis of " + link.name;
      const bool continuous = revolute && link.joint_range_lower <= -kUnlimited && link.joint_range_upper >= kUnlimited;
      const int type = continuous ? ::urdf::Joint::CONTINUOUS
                       : revolute ? ::urdf::Joint::REVOLUTE
                                  : ::urdf::Joint::PRISMATIC;
      if (uj->type != type) return "joint type of " + link.name;
      if (!continuous) {
        if (!uj->limits) return "joint limits of " + link.name;
        if (!close(uj->limits->lower, stand_in(link.joint_range_lower)) ||
            !close(uj->limits->upper, stand_in(link.joint_range_upper))) {
          return "joint range of " + link.name;
        }
      }
      if (uj->limits && link.velocity_lower == -link.velocity_upper &&
          !close(uj->limits->velocity, stand_in(link.velocity_upper))) {
        return "joint velocity of " + link.name;
      }
      if (uj->limits && link.effort_lower == -link.effort_upper &&
          !close(uj->limits->effort, stand_in(link.effort_upper))) {
        return "joint effort of " + link.name;
      }
    } else if (uj->type != ::urdf::Joint::FIXED) {
      return "joint type of " + link.name;
    }
  }

  // Forward kinematics at 20 random configurations (fixed seed), URDF's computed from
  // urdfdom's joints, ours from compute_root_relative_frames.
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), slide(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> q(model.links.size(), 0.0);
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (model.links[i].joint_type == JointType::kRevolute) q[i] = angle(rng);
      if (model.links[i].joint_type == JointType::kPrismatic) q[i] = slide(rng);
    }
    const auto ours = compute_root_relative_frames(model, q);
    std::vector<Eigen::Isometry3d> theirs(model.links.size(), Eigen::Isometry3d::Identity());
    for (std::size_t i = 1; i < model.links.size(); ++i) {
      const auto uj = u.getLink(model.links[i].name)->parent_joint;
      Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
      if (uj->type == ::urdf::Joint::REVOLUTE || uj->type == ::urdf::Joint::CONTINUOUS) {
        motion.linear() = Eigen::AngleAxisd(q[i], vec(uj->axis)).toRotationMatrix();
      } else if (uj->type == ::urdf::Joint::PRISMATIC) {
        // Choreonoid moves by axis * q with the axis as written (not normalised).
        motion.translation() = vec(uj->axis) * (q[i] * model.links[i].joint_axis.norm());
      }
      const LinkIndex parent = model.find_link(uj->parent_link_name);
      theirs[i] = theirs[static_cast<std::size_t>(parent)] * iso(uj->parent_to_joint_origin_transform) * motion;
    }
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (max_abs_diff(ours[i], theirs[i]) > 1e-9) {
        why << "FK of " << model.links[i].name << " at trial " << trial << ": " << max_abs_diff(ours[i], theirs[i]);
        return why.str();
      }
    }
  }
  return "";
}

std::size_t count_children(tinyxml2::XMLDocument& doc, const std::string& link, const char* kind) {
  std::size_t n = 0;
  for (auto* l = doc.RootElement()->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
    if (link != l->Attribute("name")) continue;
    for (auto* c = l->FirstChildElement(kind); c; c = c->NextSiblingElement(kind)) ++n;
  }
  return n;
}

}  // namespace

TEST_CASE("urdf: every loadable corpus model exports, urdfdom parses it and check_urdf exits 0") {
  const auto bodies = corpus_bodies();
  REQUIRE(!bodies.empty());
  const fs::path dir = fresh_dir("corpus");
  int loaded = 0, parsed = 0, checked = 0;
  for (const auto& body : bodies) {
    CAPTURE(body.string());
    const fs::path out = dir / (fs::relative(body, kCorpus).string() + ".d") / "model.urdf";
    Export e = export_file(body, {}, out);
    if (!e.model) continue;
    ++loaded;
    REQUIRE(e.ok);
    OutputSet output(out);
    for (auto& [path, bytes] : e.files) {
      if (path == "model.urdf")
        output.set_main(bytes);
      else
        output.add(path, bytes);
    }
    CollectingSink sink;
    REQUIRE(output.commit(sink));
    if (::urdf::parseURDF(e.urdf))
      ++parsed;
    else
      FAIL_CHECK("urdfdom cannot parse the export");
    if (run("check_urdf " + quote(out) + " > /dev/null 2>&1") == 0)
      ++checked;
    else
      FAIL_CHECK("check_urdf rejects the export");
  }
  MESSAGE("corpus: " << bodies.size() << " bodies, " << loaded << " loaded, " << parsed << " parsed by urdfdom, "
                     << checked << " accepted by check_urdf");
  CHECK(loaded >= 48);
  CHECK(parsed == loaded);
  CHECK(checked == loaded);
  fs::remove_all(dir);
}

TEST_CASE("urdf: numeric round trip through urdfdom (masses, joints, forward kinematics)") {
  int compared = 0;
  std::vector<fs::path> bodies = corpus_bodies();
  bodies.push_back(kData / "clean.body");
  // Axes of other lengths: Choreonoid moves by the axis as written, URDF by its direction.
  bodies.push_back(fs::path(BODYFMT_TEST_DATA_DIR) / "export_changed" / "axis_not_unit.body");
  bodies.push_back(fs::path(BODYFMT_TEST_DATA_DIR) / "export_changed" / "prismatic_axis_not_unit.body");
  for (const auto& body : bodies) {
    CAPTURE(body.string());
    Export e = export_file(body);
    if (!e.model) continue;
    auto u = ::urdf::parseURDF(e.urdf);
    REQUIRE(u);
    CHECK(round_trip_problem(*e.model, e.derived, *u) == "");
    ++compared;
  }
  MESSAGE("round trip: " << compared << " models");
}

TEST_CASE("urdf: each kind of loss is reported at its source line and commented in the output") {
  for (const char* name : {"pseudo_continuous_track", "extra_joint", "device", "asymmetric_velocity", "texture",
                           "free_non_root", "nonuniform_scale"}) {
    CAPTURE(name);
    const fs::path body = kData / (std::string(name) + ".body");
    Export e = export_file(body);
    REQUIRE(e.model);
    REQUIRE(e.ok);
    const auto want = marked_lines(body, "# loss");
    REQUIRE(!want.empty());
    CHECK(reported_lines(e.diagnostics, "export-loss") == want);
    for (const auto& d : e.diagnostics) CHECK(d.location.file == body.string());
    std::size_t comments = 0;
    for (std::size_t at = 0; (at = e.urdf.find("<!-- export-loss:", at)) != std::string::npos; ++at) ++comments;
    CHECK(comments == want.size());
    CHECK(::urdf::parseURDF(e.urdf) != nullptr);
  }
}

TEST_CASE("urdf: a pseudo track becomes a fixed joint with its axis recorded") {
  Export e = export_file(kData / "pseudo_continuous_track.body");
  CHECK(e.urdf.find("<!-- pseudo_continuous_track axis 0 1 0 -->") != std::string::npos);
  auto u = ::urdf::parseURDF(e.urdf);
  REQUIRE(u);
  CHECK(u->getJoint("TRACK")->type == ::urdf::Joint::FIXED);
}

TEST_CASE("urdf: names are XML-escaped and invalid URDF names are reported") {
  const fs::path body = kData / "invalid_name.body";
  Export e = export_file(body);
  REQUIRE(e.ok);
  const int line = marked_lines(body, "# name").at(0);
  CHECK(reported_lines(e.diagnostics, "export-name") == std::vector<int>{line, line});  // link and joint
  CHECK(e.urdf.find("upper arm &amp; &lt;hand&gt;") != std::string::npos);
  auto u = ::urdf::parseURDF(e.urdf);
  REQUIRE(u);
  CHECK(u->getName() == "Bad & <Names>");
  CHECK(u->getLink("upper arm & <hand>") != nullptr);
}

TEST_CASE("urdf: --devices-as-frames writes devices as fixed child links") {
  UrdfOptions options;
  options.devices_as_frames = true;
  Export e = export_file(kData / "device.body", options);
  CHECK(reported_lines(e.diagnostics, "export-loss").empty());
  auto u = ::urdf::parseURDF(e.urdf);
  REQUIRE(u);
  auto cam = u->getLink("EyeCam");
  REQUIRE(cam);
  CHECK(cam->parent_joint->type == ::urdf::Joint::FIXED);
  CHECK(cam->parent_joint->parent_link_name == "BASE");
  CHECK(cam->parent_joint->parent_to_joint_origin_transform.position.z == doctest::Approx(0.2));
  CHECK(u->getLink("Gyro") != nullptr);
}

TEST_CASE("urdf: --floating-base joins the root to a world link at its initial pose") {
  UrdfOptions options;
  options.floating_base = true;
  Export e = export_file(kCorpus / "Tank" / "SimpleTank.body", options);
  REQUIRE(e.ok);
  auto u = ::urdf::parseURDF(e.urdf);
  REQUIRE(u);
  CHECK(u->getRoot()->name == "world");
  auto j = u->getLink("CHASSIS")->parent_joint;
  REQUIRE(j);
  CHECK(j->type == ::urdf::Joint::FLOATING);
  CHECK(j->parent_to_joint_origin_transform.position.z == doctest::Approx(0.1));
  for (const auto& d : e.diagnostics) CHECK(d.message.find("initial pose") == std::string::npos);
}

// A .body written by the test (into the temp folder) from `text`.
fs::path body_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "bodyfmt_urdf_writer_bodies";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

TEST_CASE("urdf: a fixed root hangs from a world link on its named joint, at its pose") {
  Export e = export_file(body_file("fixed_root.body", R"(format: ChoreonoidBody
format_version: 2.0
name: F
links:
  - name: BASE
    joint_type: fixed
    joint_name: bolt
    translation: [1, 2, 3]
    rotation: [0, 0, 1, 90]
    mass: 1
)"));
  REQUIRE(e.ok);
  auto u = ::urdf::parseURDF(e.urdf);
  REQUIRE(u);
  CHECK(u->getRoot()->name == "world");
  auto j = u->getLink("BASE")->parent_joint;
  REQUIRE(j);
  CHECK(j->name == "bolt");
  CHECK(j->type == ::urdf::Joint::FIXED);
  const Eigen::Isometry3d X = iso(j->parent_to_joint_origin_transform);
  CHECK((X.translation() - Eigen::Vector3d(1, 2, 3)).norm() < 1e-12);
  CHECK((X.linear() - Eigen::Matrix3d(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()))).norm() < 1e-12);
  for (const auto& d : e.diagnostics) CHECK_MESSAGE(d.message.find("initial pose") == std::string::npos, d.message);
}

TEST_CASE("urdf: a free root with a joint name hangs from a world link on a floating joint, one without a name not") {
  const char* const text = R"(format: ChoreonoidBody
format_version: 2.0
name: F
links:
  - name: BASE
    joint_type: free
    joint_name: float
    mass: 1
)";
  Export e = export_file(body_file("named_free_root.body", text));
  REQUIRE(e.ok);
  auto u = ::urdf::parseURDF(e.urdf);
  REQUIRE(u);
  CHECK(u->getRoot()->name == "world");
  REQUIRE(u->getJoint("float"));
  CHECK(u->getJoint("float")->type == ::urdf::Joint::FLOATING);
  std::string unnamed = text;
  unnamed.erase(unnamed.find("    joint_name: float\n"), std::string("    joint_name: float\n").size());
  Export f = export_file(body_file("free_root.body", unnamed));
  REQUIRE(f.ok);
  auto v = ::urdf::parseURDF(f.urdf);
  REQUIRE(v);
  CHECK(v->getRoot()->name == "BASE");
}

TEST_CASE("urdf: --capsules writes a capsule as <capsule>, a reversed range is written as it is") {
  const fs::path body = body_file("capsule.body", R"(format: ChoreonoidBody
format_version: 2.0
name: C
links:
  - name: BASE
    joint_type: free
    mass: 1
    elements:
      - type: Shape
        geometry: { type: Capsule, radius: 0.1, height: 0.5 }
  - name: ARM
    parent: BASE
    joint_type: revolute
    joint_axis: Z
    joint_id: 0
    joint_range: [30, -30]
    mass: 1
)");
  UrdfOptions options;
  options.capsules = true;
  Export e = export_file(body, options);
  REQUIRE(e.ok);
  CHECK(e.urdf.find("<capsule radius=\"0.1\" length=\"0.5\"/>") != std::string::npos);
  CHECK(e.urdf.find("<limit lower=\"0.5235987755982988\" upper=\"-0.5235987755982988\"") != std::string::npos);
  Export mesh = export_file(body);
  REQUIRE(mesh.ok);
  CHECK(mesh.urdf.find("<capsule") == std::string::npos);
  CHECK(mesh.urdf.find("<mesh") != std::string::npos);
}

TEST_CASE("urdf: materials, visual/collision split, cylinder axis and defaults") {
  Export e = export_file(kData / "clean.body");
  REQUIRE(e.ok);
  CHECK(e.diagnostics.empty());
  auto u = ::urdf::parseURDF(e.urdf);
  REQUIRE(u);
  auto base = u->getLink("BASE");
  REQUIRE(base->visual);
  REQUIRE(base->visual->material);
  CHECK(base->visual->material->color.a == doctest::Approx(0.75));  // 1 - transparency
  CHECK(base->collision_array.size() == 1);
  auto arm = u->getLink("ARM");
  CHECK(arm->visual_array.size() == 1);     // Visual node: visual only
  CHECK(arm->collision_array.size() == 1);  // Collision node: collision only
  CHECK(arm->visual->geometry->type == ::urdf::Geometry::CYLINDER);
  CHECK(arm->collision->geometry->type == ::urdf::Geometry::MESH);  // a Capsule has no primitive
  // The URDF cylinder's +Z must be the Body cylinder's +Y.
  const Eigen::Vector3d axis = iso(arm->visual->origin).linear() * Eigen::Vector3d::UnitZ();
  CHECK((axis - Eigen::Vector3d::UnitY()).norm() < 1e-12);
  auto slider = u->getLink("SLIDER");  // no mass data: Choreonoid's defaults are written
  CHECK(slider->inertial->mass == 1);
  CHECK(slider->inertial->ixx == 1);
  CHECK(slider->inertial->iyy == 1);
  CHECK(slider->inertial->izz == 1);
  CHECK(e.files.count("meshes/model/ARM_shape1.stl") == 1);
}

TEST_CASE("urdf: output is deterministic (STL and DAE)") {
  for (auto format : {converters::MeshFormat::kStl, converters::MeshFormat::kDae}) {
    UrdfOptions options;
    options.mesh_format = format;
    for (const fs::path& body :
         {kCorpus / "Tank" / "SimpleTank.body", kCorpus / "SR1" / "SR1.body", kData / "clean.body"}) {
      CAPTURE(body.string());
      Export a = export_file(body, options);
      Export b = export_file(body, options);
      CHECK(a.files == b.files);
    }
  }
}

TEST_CASE("urdf: body2urdf exit codes, byte-identical runs and atomic output") {
  const fs::path dir = fresh_dir("cli");
  const std::string tool = BODYFMT_BODY2URDF;
  const fs::path out = dir / "model.urdf";
  // 0: written, nothing lost.
  CHECK(run(tool + " " + quote(kData / "clean.body") + " -o " + quote(out) + " -q 2> /dev/null") == 0);
  const std::string first = read(out);
  const std::string mesh = read(dir / "meshes" / "ARM_shape1.stl");
  CHECK(run(tool + " " + quote(kData / "clean.body") + " -o " + quote(out) + " -q 2> /dev/null") == 0);
  CHECK(read(out) == first);
  CHECK(read(dir / "meshes" / "ARM_shape1.stl") == mesh);
  // 1: written with losses.
  const fs::path lossy = dir / "track.urdf";
  CHECK(run(tool + " " + quote(kData / "pseudo_continuous_track.body") + " -o " + quote(lossy) + " 2> /dev/null") == 1);
  CHECK(fs::exists(lossy));
  // 2 with --strict: nothing written, the existing file kept.
  { std::ofstream(lossy) << "old"; }
  CHECK(run(tool + " " + quote(kData / "pseudo_continuous_track.body") + " -o " + quote(lossy) +
            " --strict 2> /dev/null") == 2);
  CHECK(read(lossy) == "old");
  // 2 when writing fails (a file where the mesh folder goes): the existing URDF is kept and
  // no temporary file is left behind.
  const fs::path blocked = fresh_dir("cli_blocked");
  { std::ofstream(blocked / "model.urdf") << "old"; }
  { std::ofstream(blocked / "meshes") << "not a folder"; }
  CHECK(run(tool + " " + quote(kData / "clean.body") + " -o " + quote(blocked / "model.urdf") + " 2> /dev/null") == 2);
  CHECK(read(blocked / "model.urdf") == "old");
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(blocked)) ++entries;
  CHECK(entries == 2);
  fs::remove_all(blocked);
  fs::remove_all(dir);
}

// SR1: the corpus has SR1.urdf, written by hand for the same robot. Every difference from our
// export, and why:
// * Link and joint names, the tree, joint types and axes, masses, centres of mass and joint
//   origins agree (within 1e-12; our CoMs such as 0.10000000000000002 are the exact doubles
//   of Choreonoid's combination, the hand file writes 0.1).
// * Inertia: both write Choreonoid's default identity tensor (SR1.body gives no inertia).
// * Joint ranges: SR1.body has degrees; we write the exact radians (90 deg ->
//   1.5707963267948966), the hand file 1.57 / 3.14 or 12 significant digits, so they differ
//   by up to 1.6e-3 rad (1.57 vs pi/2) and 1.6e-3 (3.14 vs pi).
// * effort / velocity: SR1.body sets no max_joint_effort / max_joint_velocity (unlimited in
//   Choreonoid); the hand file invents effort 500 and velocity 10 (and velocity 0 for
//   RARM_ELBOW, a typo that would freeze the joint in MoveIt), we write the documented
//   stand-in 1e30 (SUPPORT.md).
// * CHEST has 6 visuals/collisions in ours, 4 in the hand file: the two camera bodies
//   (Cylinder shapes under the LeftCamera/RightCamera devices) belong to the link's shape in
//   Choreonoid, and the hand file leaves them out.
// * The hand file omits the devices (cameras, force sensors, gyro, accelerometer, IMU) and the
//   'Sole' contact material silently; we report each as export-loss.
// * The root's initial pose (WAIST at z = 0.7135) is in neither URDF (ours reports it).
// * The hand file's fourth CHEST visual has a <material> without a name. urdfdom logs "Visual
//   material must contain a name attribute" / "Could not parse visual element for Link
//   [CHEST]" and keeps only part of CHEST's visuals and collisions, although check_urdf still
//   exits 0; so the shape counts below come from the XML. Ours parses without a message.
// * Materials: the hand file names them after the Body appearances; ours are material_N by
//   first use, same colours.
TEST_CASE("urdf: SR1 export against the hand-written SR1.urdf") {
  Export e = export_file(kCorpus / "SR1" / "SR1.body");
  REQUIRE(e.ok);
  auto ours = ::urdf::parseURDF(e.urdf);
  auto hand = ::urdf::parseURDF(read(kCorpus / "SR1" / "SR1.urdf"));
  REQUIRE(ours);
  REQUIRE(hand);
  tinyxml2::XMLDocument hand_xml;
  REQUIRE(hand_xml.LoadFile((kCorpus / "SR1" / "SR1.urdf").c_str()) == tinyxml2::XML_SUCCESS);
  CHECK(ours->links_.size() == hand->links_.size());
  CHECK(ours->joints_.size() == hand->joints_.size());
  CHECK(ours->getRoot()->name == hand->getRoot()->name);
  for (const auto& link_entry : hand->links_) {
    const std::string& name = link_entry.first;  // not a structured binding: CAPTURE needs a variable
    const auto& hl = link_entry.second;
    CAPTURE(name);
    auto ol = ours->getLink(name);
    REQUIRE(ol);
    REQUIRE(ol->inertial);
    REQUIRE(hl->inertial);
    CHECK(ol->inertial->mass == doctest::Approx(hl->inertial->mass).epsilon(1e-12));
    CHECK((iso(ol->inertial->origin).translation() - iso(hl->inertial->origin).translation()).norm() < 1e-12);
    CHECK(ol->inertial->ixx == hl->inertial->ixx);
    CHECK(ol->inertial->ixy == hl->inertial->ixy);
    CHECK(ol->inertial->izz == hl->inertial->izz);
    // Counted in the XML: urdfdom reads the hand file's CHEST only partly (see above).
    const std::size_t extra = name == "CHEST" ? 2 : 0;  // the camera bodies
    CHECK(ol->visual_array.size() == count_children(hand_xml, name, "visual") + extra);
    CHECK(ol->collision_array.size() == count_children(hand_xml, name, "collision") + extra);
  }
  for (const auto& joint_entry : hand->joints_) {
    const std::string& name = joint_entry.first;
    const auto& hj = joint_entry.second;
    CAPTURE(name);
    auto oj = ours->getJoint(name);
    REQUIRE(oj);
    CHECK(oj->type == hj->type);
    CHECK(oj->parent_link_name == hj->parent_link_name);
    CHECK(oj->child_link_name == hj->child_link_name);
    CHECK(max_abs_diff(iso(oj->parent_to_joint_origin_transform), iso(hj->parent_to_joint_origin_transform)) < 1e-12);
    CHECK((vec(oj->axis) - vec(hj->axis)).norm() < 1e-12);
    REQUIRE(oj->limits);
    REQUIRE(hj->limits);
    CHECK(std::abs(oj->limits->lower - hj->limits->lower) < 2e-3);  // 1.57 / 3.14 in the hand file
    CHECK(std::abs(oj->limits->upper - hj->limits->upper) < 2e-3);
    CHECK(oj->limits->effort == bodyfmt::urdf::kUnlimitedStandIn);    // hand file: 500
    CHECK(oj->limits->velocity == bodyfmt::urdf::kUnlimitedStandIn);  // hand file: 10 (0 on RARM_ELBOW)
    CHECK(hj->limits->effort == 500);
  }
}
