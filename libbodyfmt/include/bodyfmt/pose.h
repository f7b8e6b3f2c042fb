#pragma once
/// Forward kinematics by joint name: which joints move, a joint vector from named positions,
/// and the world frame of every link at that pose (compute_world_frames underneath). What
/// `bodyinfo --pose` prints and `bodyview`'s page is checked against.

#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <Eigen/Geometry>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// The name a joint is set by: the link's joint name, else the link name (as Choreonoid).
std::string_view joint_name_of(const Link& link);

/// Links whose joint moves with a position (revolute, prismatic), in link order.
std::vector<LinkIndex> movable_joints(const Model& model);

/// A joint position by name (joint_name_of) or by link name: radians or metres.
struct JointPosition {
  std::string name;
  double value = 0;
};

struct JointVector {
  std::vector<double> q;              ///< indexed like Model::links (compute_world_frames); 0 when not named
  std::vector<std::string> problems;  ///< one sentence per name that is unknown, fixed or not finite
};

/// The joint vector for `positions`; names that match no movable joint are problems, not set.
JointVector joint_vector(const Model& model, const std::vector<JointPosition>& positions);

/// Parses "NAME=VALUE,NAME=VALUE" (empty: the zero pose). Problems name the bad item.
std::pair<std::vector<JointPosition>, std::vector<std::string>> parse_joint_positions(std::string_view text);

/// X_WL of every link at the positions (unnamed joints at 0), the root at its initial pose.
std::vector<Eigen::Isometry3d> forward_kinematics(const Model& model, const std::vector<JointPosition>& positions);

}  // namespace bodyfmt
#pragma GCC visibility pop
