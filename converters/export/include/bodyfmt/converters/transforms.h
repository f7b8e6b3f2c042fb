#pragma once
/// Rotations and placements as the target formats spell them.
#include <Eigen/Geometry>

#include <optional>

namespace bodyfmt::converters {

/// Roll, pitch, yaw with R = Rz(yaw) Ry(pitch) Rx(roll) (URDF, SDFormat). Yaw is taken first
/// and roll from what is left, so that near pitch = ±90° (gimbal lock) the triple still
/// reproduces R to rounding error.
Eigen::Vector3d rpy_of(const Eigen::Matrix3d& R);

/// L = rotation · diag(scale) with a proper rotation: what a mesh scale or a primitive's size
/// can carry.
struct ScaledRotation {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d scale;
};
/// Empty when L shears or mirrors (or scales an axis to zero).
std::optional<ScaledRotation> decompose(const Eigen::Matrix3d& L);

/// |a - b| within 1e-12 of the larger magnitude: "the same scale" for uniform-scale checks.
bool nearly_equal(double a, double b);

}  // namespace bodyfmt::converters
