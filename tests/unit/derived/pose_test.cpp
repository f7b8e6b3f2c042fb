// bodyfmt/pose.h: joint positions by name and forward kinematics, with values derived by hand.
#include <bodyfmt/pose.h>

#include <doctest/doctest.h>

#include <cmath>

using namespace bodyfmt;

namespace {

// base (fixed root at z = 1) -> arm (revolute about +Z, 1 m along x, joint "shoulder")
// -> slide (prismatic along +X, 0.5 m along x) -> tool (fixed)
Model arm() {
  Model m;
  m.links.resize(4);
  m.links[0].name = "base";
  m.links[0].X_PL.translation() = Eigen::Vector3d(0, 0, 1);
  m.links[1].name = "arm";
  m.links[1].joint_name = "shoulder";
  m.links[1].parent = 0;
  m.links[1].joint_type = JointType::kRevolute;
  m.links[1].X_PL.translation() = Eigen::Vector3d(1, 0, 0);
  m.links[2].name = "slide";
  m.links[2].parent = 1;
  m.links[2].joint_type = JointType::kPrismatic;
  m.links[2].joint_axis = Eigen::Vector3d(1, 0, 0);
  m.links[2].X_PL.translation() = Eigen::Vector3d(0.5, 0, 0);
  m.links[3].name = "tool";
  m.links[3].parent = 2;
  m.links[0].children = {1};
  m.links[1].children = {2};
  m.links[2].children = {3};
  return m;
}

}  // namespace

TEST_CASE("pose: a quarter turn of the shoulder and 0.25 m of the slide place the tool by hand") {
  const Model m = arm();
  CHECK(movable_joints(m) == std::vector<LinkIndex>{1, 2});
  CHECK(joint_name_of(m.links[1]) == "shoulder");
  CHECK(joint_name_of(m.links[2]) == "slide");
  // The shoulder turns +90 deg about Z: the slide's offset (0.5 + 0.25 along x) now points along +y.
  const auto X = forward_kinematics(m, {{"shoulder", M_PI / 2}, {"slide", 0.25}});
  const Eigen::Vector3d tool = X[3].translation();
  CHECK(std::abs(tool.x() - 1.0) < 1e-15);
  CHECK(std::abs(tool.y() - 0.75) < 1e-15);
  CHECK(std::abs(tool.z() - 1.0) < 1e-15);
  CHECK(std::abs(X[3].linear()(1, 0) - 1.0) < 1e-15);  // the tool's x axis is world +y
  // By link name as well as joint name; the zero pose is the file's.
  const auto by_link = forward_kinematics(m, {{"arm", M_PI / 2}, {"slide", 0.25}});
  CHECK(by_link[3].isApprox(X[3], 1e-15));
  CHECK(forward_kinematics(m, {})[3].translation().isApprox(Eigen::Vector3d(1.5, 0, 1), 1e-15));
}

TEST_CASE("pose: unknown, fixed and non-finite joints are problems, not set") {
  const Model m = arm();
  const JointVector q = joint_vector(m, {{"elbow", 1}, {"tool", 1}, {"shoulder", NAN}, {"slide", 0.1}});
  REQUIRE(q.problems.size() == 3);
  CHECK(q.problems[0].find("no joint or link named 'elbow'") != std::string::npos);
  CHECK(q.problems[1].find("is fixed") != std::string::npos);
  CHECK(q.problems[2].find("not finite") != std::string::npos);
  CHECK(q.q == std::vector<double>{0, 0, 0.1, 0});
}

TEST_CASE("pose: NAME=VALUE lists parse, a bad item is named") {
  const auto good = parse_joint_positions(" a=1.5, b = -2e-3 ");
  const std::vector<JointPosition>& positions = good.first;
  REQUIRE(positions.size() == 2);
  CHECK(positions[1].name == "b");
  CHECK(positions[1].value == -2e-3);
  CHECK(good.second.empty());
  CHECK(parse_joint_positions("").first.empty());
  for (const char* bad : {"a", "a=", "=1", "a=1x", "a=nan", "a=1e999", "a=1,,b=2"}) {
    CAPTURE(bad);
    CHECK(parse_joint_positions(bad).second.size() == 1);
  }
}
