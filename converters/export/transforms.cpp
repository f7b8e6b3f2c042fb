#include <bodyfmt/converters/transforms.h>

#include <algorithm>
#include <cmath>

namespace bodyfmt::converters {

Eigen::Vector3d rpy_of(const Eigen::Matrix3d& R) {
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const Eigen::Matrix3d rest = Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()).toRotationMatrix() *
                               Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R;
  const double roll = std::atan2(rest(2, 1), rest(2, 2));
  return {roll, pitch, yaw};
}

std::optional<ScaledRotation> decompose(const Eigen::Matrix3d& L) {
  ScaledRotation out;
  out.scale = L.colwise().norm().transpose();
  if ((out.scale.array() <= 0).any()) return std::nullopt;
  out.rotation = L * out.scale.cwiseInverse().asDiagonal();
  if ((out.rotation.transpose() * out.rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-12 ||
      out.rotation.determinant() < 0) {
    return std::nullopt;
  }
  return out;
}

bool nearly_equal(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); }

}  // namespace bodyfmt::converters
