#include <bodyfmt/derived.h>

namespace bodyfmt {

MassProperties compute_mass_properties(const Link& link) {
  MassProperties result;  // Choreonoid's defaults when nothing contributes (§6.4 rule 4)
  if (link.mass_contributions.empty()) return result;
  double M = 0;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (const MassContribution& c : link.mass_contributions) {
    M += c.mass;
    weighted += c.mass * c.center_of_mass;
  }
  result.mass = M;
  if (M == 0) {
    // §6.4 rule 3: a massless combination drops the individual inertias too.
    result.center_of_mass.setZero();
    result.inertia.setZero();
    return result;
  }
  const Eigen::Vector3d C = weighted / M;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (const MassContribution& c : link.mass_contributions) {
    const Eigen::Vector3d d = C - c.center_of_mass;
    I += c.inertia + c.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  result.center_of_mass = C;
  result.inertia = I;
  return result;
}

}  // namespace bodyfmt
