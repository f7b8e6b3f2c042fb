// Joint-space quantities computed from the model's derived data alone, without Simbody: the
// independent references the checks and unit tests compare the simulation with.

#include <bodyfmt/dynamics/simulation.h>

namespace bodyfmt::dynamics {
namespace {

bool in_subtree(const Model& model, LinkIndex link, LinkIndex top) {
  for (LinkIndex k = link; k >= 0; k = model.links[k].parent)
    if (k == top) return true;
  return false;
}

}  // namespace

double subtree_axis_inertia(const Model& model, const Derived& derived, LinkIndex link, const std::vector<double>& q,
                            const std::vector<Eigen::Matrix3d>& inertias) {
  const std::vector<Eigen::Isometry3d> X = compute_world_frames(model, q);
  const Link& joint = model.links[link];
  const Eigen::Vector3d a = (X[link].linear() * joint.joint_axis.normalized()).normalized();
  const Eigen::Vector3d o = X[link].translation();
  double total = 0;
  for (std::size_t k = 0; k < model.links.size(); ++k) {
    if (!in_subtree(model, static_cast<LinkIndex>(k), link)) continue;
    const MassProperties& mp = derived.mass[k];
    const Eigen::Matrix3d& Ic = inertias.empty() ? mp.inertia : inertias[k];
    const Eigen::Matrix3d R = X[k].linear();
    if (joint.joint_type == JointType::kPrismatic) {
      total += mp.mass;
      continue;
    }
    // Parallel axes: aᵀ R I_c Rᵀ a + m · (distance of the centre of mass from the axis)².
    const Eigen::Vector3d r = X[k] * mp.center_of_mass - o;
    const Eigen::Vector3d perpendicular = r - a * a.dot(r);
    total += a.dot(R * Ic * R.transpose() * a) + mp.mass * perpendicular.squaredNorm();
  }
  return total;
}

double subtree_gravity_torque(const Model& model, const Derived& derived, LinkIndex link, const std::vector<double>& q,
                              double gravity) {
  const std::vector<Eigen::Isometry3d> X = compute_world_frames(model, q);
  const Link& joint = model.links[link];
  const Eigen::Vector3d a = (X[link].linear() * joint.joint_axis.normalized()).normalized();
  const Eigen::Vector3d o = X[link].translation();
  double total = 0;
  for (std::size_t k = 0; k < model.links.size(); ++k) {
    if (!in_subtree(model, static_cast<LinkIndex>(k), link)) continue;
    const MassProperties& mp = derived.mass[k];
    const Eigen::Vector3d weight(0, 0, -mp.mass * gravity);
    if (joint.joint_type == JointType::kPrismatic) {
      total += a.dot(weight);
    } else {
      total += a.dot((X[k] * mp.center_of_mass - o).cross(weight));
    }
  }
  return total;
}

}  // namespace bodyfmt::dynamics
