// Loader unit tests for load/body_reader.cpp: header keys (body-format-spec §2.1), the link
// tree (§5.2), extra joints (§12) and the resulting link frames (§6.1 kinematics).

#include "support/load_helpers.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/derived.h>

#include <cmath>

using namespace bodyfmt;
using bodyfmt::test::load;
using bodyfmt::test::load_v2;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

namespace {
using bodyfmt::kPi;

bool near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double eps = 1e-12) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a - b).cwiseAbs().maxCoeff() <= eps;
}
}  // namespace

// ---------------------------------------------------------------------------------------
// Header

TEST_CASE("load: minimal body, name defaults to the file stem") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
links:
  - name: A
)");
  CHECK(r.m().name == "test");
  CHECK(r.m().format_version == 2.0);
  CHECK(r.m().links.size() == 1);
  CHECK(r.m().source_file == "test.body");
  r.expect_clean();
}

TEST_CASE("load: missing format is fatal load-format at the top mapping") {
  auto r = load(R"(
format_version: 2.0
links:
  - name: A
)");
  CHECK_FALSE(r.model.has_value());
  auto d = r.take("load-format");
  CHECK(d.severity == Severity::kFatal);
  CHECK(pos(d) == Pos{1, 1});
  r.expect_clean();
}

TEST_CASE("load: wrong format is fatal load-format at the value") {
  auto r = load(R"(
format: ChoreonoidScene
format_version: 2.0
links:
  - name: A
)");
  CHECK_FALSE(r.model.has_value());
  auto d = r.take("load-format");
  CHECK(d.severity == Severity::kFatal);
  CHECK(pos(d) == Pos{1, 9});
  r.expect_clean();
}

TEST_CASE("load: missing format_version is fatal load-format-version") {
  auto r = load(R"(
format: ChoreonoidBody
links:
  - name: A
)");
  CHECK_FALSE(r.model.has_value());
  CHECK(pos(r.take("load-format-version")) == Pos{1, 1});
  r.expect_clean();
}

TEST_CASE("load: format_version 2.1 is rejected, 1.3 is accepted") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.1
links:
  - name: A
)");
  CHECK_FALSE(r.model.has_value());
  auto d = r.take("load-format-version");
  CHECK(d.severity == Severity::kFatal);
  CHECK(pos(d) == Pos{2, 17});
  r.expect_clean();

  auto ok = load(R"(
format: ChoreonoidBody
formatVersion: 1.3
links:
  - name: A
)");
  CHECK(ok.m().format_version == 1.3);
  ok.take("load-legacy-key");
  ok.expect_clean();
}

TEST_CASE("load: angle_unit radian in format 2.0 is fatal units-radian-in-2.0 at the value") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
angle_unit: radian
links:
  - name: A
)");
  CHECK_FALSE(r.model.has_value());
  auto d = r.take("units-radian-in-2.0");
  CHECK(d.severity == Severity::kFatal);
  CHECK(pos(d) == Pos{3, 13});
  r.expect_clean();
}

TEST_CASE("load: angle_unit other than degree/radian is fatal load-angle-unit") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 1.0
angle_unit: Degree
links:
  - name: A
)");
  CHECK_FALSE(r.model.has_value());
  auto d = r.take("load-angle-unit");
  CHECK(d.severity == Severity::kFatal);
  CHECK(pos(d) == Pos{3, 13});
  r.expect_clean();
}

TEST_CASE("load: angle_unit degree is accepted explicitly") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
angle_unit: degree
links:
  - name: A
    rotation: [1, 0, 0, 180]
)");
  CHECK(r.m().angles_in_degrees);
  Eigen::Matrix3d Rx180;
  Rx180 << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  CHECK(near(r.link("A").X_PL.linear(), Rx180));
  r.expect_clean();
}

TEST_CASE("load: missing links is fatal load-no-links") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
name: Robot
)");
  CHECK_FALSE(r.model.has_value());
  auto d = r.take("load-no-links");
  CHECK(d.severity == Severity::kFatal);
  CHECK(pos(d) == Pos{1, 1});
  r.expect_clean();
}

TEST_CASE("load: an empty links list is load-no-links") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
links: []
)");
  CHECK_FALSE(r.model.has_value());
  CHECK(pos(r.take("load-no-links")) == Pos{3, 8});  // "No link is contained in the links listing"
  CHECK(pos(r.take("load-no-links")) == Pos{3, 8});  // "There is no link defined"
  r.expect_clean();
}

TEST_CASE("load: a scalar as the whole document is fatal") {
  auto r = load("just a scalar\n");
  CHECK_FALSE(r.model.has_value());
  auto d = r.take("load-top-level");
  CHECK(d.severity == Severity::kFatal);
  CHECK(pos(d) == Pos{1, 1});
  r.expect_clean();
}

TEST_CASE("load: body_handlers and name are read") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
name: Robot
body_handlers: [HandlerA, HandlerB]
links:
  - name: A
)");
  CHECK(r.m().name == "Robot");
  CHECK(r.m().body_handlers == std::vector<std::string>{"HandlerA", "HandlerB"});
  r.expect_clean();
}

// ---------------------------------------------------------------------------------------
// Link tree (§5.2). load_v2: "links:" is line 3.

TEST_CASE("load: links are in depth-first pre-order, children in definition order") {
  auto r = load_v2(R"(
links:
  - name: ROOT
  - name: C2
    parent: B
  - name: B
    parent: ROOT
  - name: C1
    parent: B
  - name: A
    parent: ROOT
)");
  // Children of ROOT in definition order: B, A; of B: C2, C1.
  // Pre-order: ROOT, B, C2, C1, A.
  const auto& links = r.m().links;
  REQUIRE(links.size() == 5);
  CHECK(links[0].name == "ROOT");
  CHECK(links[1].name == "B");
  CHECK(links[2].name == "C2");
  CHECK(links[3].name == "C1");
  CHECK(links[4].name == "A");
  CHECK(links[0].parent == -1);
  CHECK(links[1].parent == 0);
  CHECK(links[2].parent == 1);
  CHECK(links[3].parent == 1);
  CHECK(links[4].parent == 0);
  CHECK(links[0].children == std::vector<LinkIndex>{1, 4});
  CHECK(links[1].children == std::vector<LinkIndex>{2, 3});
  CHECK(r.m().find_link("C1") == 3);
  r.expect_clean();
}

TEST_CASE("load: root_link selects the root, unknown root_link is fatal") {
  auto r = load(R"(
format: ChoreonoidBody
format_version: 2.0
root_link: B
links:
  - name: A
    parent: B
  - name: B
)");
  const auto& links = r.m().links;
  REQUIRE(links.size() == 2);
  CHECK(links[0].name == "B");
  CHECK(links[1].name == "A");
  CHECK(links[1].parent == 0);
  r.expect_clean();

  auto bad = load(R"(
format: ChoreonoidBody
format_version: 2.0
rootLink: Q
links:
  - name: A
)");
  CHECK_FALSE(bad.model.has_value());
  auto d = bad.take("structure-root-link");
  CHECK(d.severity == Severity::kFatal);
  CHECK(pos(d) == Pos{3, 11});
  bad.take("load-legacy-key");
  bad.expect_clean();
}

TEST_CASE("load: unknown parent is structure-unknown-parent with did-you-mean") {
  auto r = load_v2(R"(
links:
  - name: BASE
  - name: ARM
    parent: BAES
)");
  auto d = r.take("structure-unknown-parent");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{6, 13});
  CHECK(d.fix_hint.find("BASE") != std::string::npos);
  r.expect_clean();
}

// Issue 47: the tutorial's `parent: CHASIS` had a did-you-mean only in the hint, which editors
// hide, and no edit. The nearest name is now in the message, and the rename is an unsafe fix-it
// (the link is then attached) when one name is nearest.
TEST_CASE("load: an unknown parent names the nearest link in its message, with the rename as a fix-it") {
  const std::string text =
      "format: ChoreonoidBody\nformat_version: 2.0\nlinks:\n  - name: CHASSIS\n  - name: TURRET_Y\n"
      "    parent: CHASIS\n";
  auto r = load(text);
  auto d = r.take("structure-unknown-parent");
  CHECK(pos(d) == Pos{6, 13});
  CHECK(d.message.find("did you mean \"CHASSIS\"?") != std::string::npos);
  REQUIRE(d.fixes.size() == 1);
  const FixIt& fix = d.fixes[0];
  CHECK(fix.safety == FixSafety::kUnsafe);
  CHECK(text.substr(fix.begin, fix.end - fix.begin) == "CHASIS");
  CHECK(fix.original == "CHASIS");
  CHECK(fix.replacement == "CHASSIS");
  CHECK(fix.line == 6);
  CHECK(fix.column == 13);
  r.expect_clean();
}

TEST_CASE("load: an unknown parent as near to two links lists both and has no fix-it") {
  auto r = load_v2(R"(
links:
  - name: ARM_L
  - name: ARM_R
    parent: ARM_L
  - name: HAND
    parent: "ARM_X"
)");
  auto d = r.take("structure-unknown-parent");
  CHECK(d.message.find("did you mean \"ARM_L\" or \"ARM_R\"?") != std::string::npos);
  CHECK(d.fixes.empty());
  r.expect_clean();
  // Through an alias the name is shared text: no edit. Quoted, the edit is inside the quotes.
  auto aliased = load_v2(R"(
definitions: { p: &P BAES }
links:
  - name: BASE
  - name: ARM
    parent: *P
  - name: LEG
    parent: "BSAE"
)");
  auto a = aliased.take("structure-unknown-parent");
  CHECK(a.fixes.empty());
  auto q = aliased.take("structure-unknown-parent");
  REQUIRE(q.fixes.size() == 1);
  CHECK(q.fixes[0].column == 14);
  CHECK(q.fixes[0].replacement == "BASE");
  aliased.drop_notes("load-info-key");
  aliased.expect_clean();
}

TEST_CASE("load: duplicate link name is structure-duplicate-link at the second name") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
  - name: B
    parent: A
)");
  auto d = r.take("structure-duplicate-link");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{7, 11});
  r.expect_clean();
}

TEST_CASE("load: a parent cycle is structure-cycle at the closing parent") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: C
  - name: C
    parent: B
)");
  // B -> C is accepted first; C -> B would close the loop B -> C -> B.
  auto d = r.take("structure-cycle");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{8, 13});
  // B hangs off C, which has no parent: B is not connected to the root.
  CHECK(pos(r.take("structure-unreachable")) == Pos{5, 5});
  r.expect_clean();
}

TEST_CASE("load: a non-root link without parent is structure-no-parent") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
)");
  auto d = r.take("structure-no-parent");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{5, 5});
  r.expect_clean();
}

TEST_CASE("load: the root link with a parent is structure-root-parent") {
  auto r = load_v2(R"(
links:
  - name: A
    parent: B
  - name: B
    parent: A
)");
  auto d = r.take("structure-root-parent");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{5, 13});
  r.expect_clean();
}

TEST_CASE("load: root-relative and world frames of a revolute/prismatic chain at non-zero q") {
  auto r = load_v2(R"(
links:
  - name: BASE
    translation: [0, 0, 1]
    joint_type: free
  - name: J1
    parent: BASE
    translation: [1, 0, 0]
    joint_type: revolute
    joint_axis: Z
  - name: J2
    parent: J1
    translation: [1, 0, 0]
    rotation: [1, 0, 0, 90]
    joint_type: prismatic
    joint_axis: Z
  - name: TIP
    parent: J2
    translation: [0, 0, 0.5]
)");
  r.expect_clean();
  const Model& model = r.m();
  REQUIRE(model.links.size() == 4);
  const std::vector<double> q = {0, kPi / 2, 0.25, 0};
  // J1: p = (1,0,0), R = Rz(90).
  // J2: p = p1 + R1 (b + Rb a q) = (1,0,0) + Rz90 ((1,0,0) + Rx90 (0,0,0.25))
  //        = (1,0,0) + Rz90 (1,-0.25,0) = (1,0,0) + (0.25,1,0) = (1.25,1,0);
  //     R = Rz90 Rx90 = [0 0 1; 1 0 0; 0 1 0].
  // TIP: p = (1.25,1,0) + R2 (0,0,0.5) = (1.25,1,0) + (0.5,0,0) = (1.75,1,0).
  Eigen::Matrix3d Rz90;
  Rz90 << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  Eigen::Matrix3d R2;
  R2 << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  const auto X_RL = compute_root_relative_frames(model, q);
  REQUIRE(X_RL.size() == 4);
  CHECK(X_RL[0].matrix().isIdentity());
  CHECK(near(X_RL[1].translation(), Eigen::Vector3d(1, 0, 0)));
  CHECK(near(X_RL[1].linear(), Rz90));
  CHECK(near(X_RL[2].translation(), Eigen::Vector3d(1.25, 1, 0)));
  CHECK(near(X_RL[2].linear(), R2));
  CHECK(near(X_RL[3].translation(), Eigen::Vector3d(1.75, 1, 0)));
  CHECK(near(X_RL[3].linear(), R2));
  // World: the root sits at its translation (0,0,1).
  const auto X_WL = compute_world_frames(model, q);
  CHECK(near(X_WL[0].translation(), Eigen::Vector3d(0, 0, 1)));
  CHECK(near(X_WL[3].translation(), Eigen::Vector3d(1.75, 1, 1)));
  CHECK(near(X_WL[3].linear(), R2));
  // At q = 0: TIP at (1,0,0) + (1,0,0) + Rx90 (0,0,0.5) = (2,-0.5,0) relative to the root.
  const auto X0 = compute_root_relative_frames(model);
  CHECK(near(X0[3].translation(), Eigen::Vector3d(2, -0.5, 0)));
}

// ---------------------------------------------------------------------------------------
// Extra joints (§12)

TEST_CASE("load: extra joints, axis normalised, unknown link error, link1_local_pos ignored") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
extra_joints:
  - link1_name: A
    link2_name: B
    joint_type: hinge
    axis: [0, 3, 4]
    translation_in_link1: [0.1, 0, 0]
    translation_in_link2: [0, 0.2, 0]
  - link1_name: A
    link2_name: C
    joint_type: ball
  - link1_name: A
    link2_name: B
    joint_type: piston
    link1_local_pos: [1, 2, 3]
)");
  const auto& joints = r.m().extra_joints;
  REQUIRE(joints.size() == 2);
  CHECK(joints[0].type == "hinge");
  CHECK(joints[0].link1 == 0);
  CHECK(joints[0].link2 == 1);
  CHECK(near(joints[0].axis, Eigen::Vector3d(0, 0.6, 0.8)));
  CHECK(joints[0].X_1J.translation() == Eigen::Vector3d(0.1, 0, 0));
  CHECK(joints[0].X_2J.translation() == Eigen::Vector3d(0, 0.2, 0));
  CHECK(joints[1].type == "piston");
  CHECK(joints[1].axis == Eigen::Vector3d(1, 0, 0));  // default +X
  CHECK(joints[1].X_1J.translation() == Eigen::Vector3d::Zero());
  auto d = r.take("extra-joint-link");
  CHECK(d.severity == Severity::kError);
  CHECK(pos(d) == Pos{15, 17});
  auto w = r.take("load-ignored-key");
  CHECK(w.severity == Severity::kWarning);
  CHECK(pos(w) == Pos{20, 22});
  r.expect_clean();
}

TEST_CASE("load: extra joint with a bad joint type is extra-joint-type") {
  auto r = load_v2(R"(
links:
  - name: A
  - name: B
    parent: A
extra_joints:
  - {link1_name: A, link2_name: B, joint_type: revolute}
)");
  CHECK(pos(r.take("extra-joint-type")) == Pos{8, 48});
  CHECK(r.m().extra_joints.empty());
  r.expect_clean();
}

TEST_CASE("load: a SubBody without a parent drops its links and the extra joints between them") {
  const std::string main = std::string(BODYFMT_TEST_DATA_DIR) + "/hostile/subbody_without_parent/main.body";
  CollectingSink sink;
  const std::optional<Model> model = load_body(main, {}, sink);
  REQUIRE(model);
  CHECK(model->links.size() == 1);
  CHECK(model->extra_joints.empty());
  CHECK(sink.has("structure-no-parent"));
  CHECK(sink.has("structure-unreachable"));
}

TEST_CASE("load: an extra joint's axis is read for a hinge or a piston only") {
  auto r = load_v2(R"(
links:
  - name: A
  - {name: B, parent: A}
extra_joints:
  - {link1_name: A, link2_name: B, joint_type: ball, axis: [0, 0, 0]}
  - {link1_name: A, link2_name: B, joint_type: fixed, jointAxis: X}
  - {link1_name: A, link2_name: B, joint_type: hinge, axis: [0, 0, 0]}
)");
  // StdBodyLoader::readExtraJoint: extractEigen(axis) only for Hinge and Piston, so the ball's
  // zero vector and the fixed joint's symbol are never read; the hinge's zero axis is.
  CHECK(pos(r.take("load-ignored-key")) == Pos{7, 60});
  CHECK(pos(r.take("load-ignored-key")) == Pos{8, 66});
  CHECK(pos(r.take("extra-joint-axis")) == Pos{9, 61});
  r.take("load-legacy-key");  // jointAxis
  CHECK_FALSE(r.has("load-type"));
  r.expect_clean();
}

TEST_CASE("load: links given as a mapping refuse an inner type other than the key") {
  auto r = load_v2(R"(
links:
  Link:
    type: SubBody
    name: A
)");
  // StdBodyLoader::readNodeInLinks: "The node type ... is different from the type ...".
  CHECK(pos(r.take("load-type-mismatch")) == Pos{5, 11});
  r.take("load-no-links");  // the only link was refused
  r.expect_clean();
}
