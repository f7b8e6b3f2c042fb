#include "derived/frames_internal.h"

#include <bodyfmt/derived.h>

namespace bodyfmt {
namespace {

// body-format-spec §6.1 kinematics: the joint sits at the link origin, its axis in the link
// frame after the offset rotation.
Eigen::Isometry3d joint_motion(const Link& link, double q) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (q == 0) return X;
  if (link.joint_type == JointType::kRevolute) {
    X.linear() = Eigen::AngleAxisd(q, link.joint_axis.normalized()).toRotationMatrix();
  } else if (link.joint_type == JointType::kPrismatic) {
    X.translation() = link.joint_axis * q;
  }
  return X;
}

// Every storage multiplies transforms alike (linear and translation parts), so the compact
// frames hold the same values as the isometries.
template <typename Frame>
std::vector<Frame> frames(const Model& model, const std::vector<double>& q, const Frame& X_W_root) {
  std::vector<Frame> X(model.links.size(), Frame::Identity());
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    const double qi = i < q.size() ? q[i] : 0.0;
    if (link.parent < 0) {
      X[i] = Frame((X_W_root * joint_motion(link, qi)).matrix());
    } else {
      // Links are in depth-first order, so the parent's frame is already known.
      X[i] = Frame((X[static_cast<std::size_t>(link.parent)] * link.X_PL * joint_motion(link, qi)).matrix());
    }
  }
  return X;
}

}  // namespace

std::vector<Eigen::Isometry3d> compute_root_relative_frames(const Model& model, const std::vector<double>& q) {
  return frames(model, q, Eigen::Isometry3d::Identity());
}

std::vector<Eigen::Isometry3d> compute_world_frames(const Model& model, const std::vector<double>& q) {
  if (model.links.empty()) return {};
  return frames(model, q, as_isometry(model.root().X_PL));
}

namespace detail {

std::vector<Eigen::AffineCompact3d> compact_root_relative_frames(const Model& model) {
  return frames(model, {}, Eigen::AffineCompact3d::Identity());
}

std::vector<Eigen::AffineCompact3d> compact_world_frames(const Model& model) {
  if (model.links.empty()) return {};
  return frames(model, {}, model.root().X_PL);
}

}  // namespace detail

}  // namespace bodyfmt
