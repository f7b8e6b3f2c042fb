#pragma once
/// Inertia tensors: one symmetrisation, one principal decomposition and one balancing function,
/// shared by bodycheck's inertia rules and fix hint, the exporters and the dynamics checker, so
/// that every tool reports and writes the same numbers.

#include <bodyfmt/export.h>

#include <Eigen/Core>

#include <optional>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// (I + Iᵀ) / 2. Choreonoid keeps the 9 numbers as given; every consumer that needs a tensor
/// (URDF, MJCF, Simbody) needs a symmetric one.
Eigen::Matrix3d symmetrized_inertia(const Eigen::Matrix3d& inertia);

struct PrincipalInertia {
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();   ///< ascending
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< columns, in the tensor's axes
  /// Read off a diagonal tensor, without eigen-solver rounding (MuJoCo checks those exactly).
  bool exact = false;
};

/// Principal moments and axes of the symmetrised tensor.
PrincipalInertia principal_inertia(const Eigen::Matrix3d& inertia);

/// Why a tensor needs balancing, from its principal moments, with the tolerances of
/// bodycheck's inertia rules: none for a diagonal tensor (MuJoCo checks those exactly),
/// eigen-solver rounding otherwise.
struct InertiaValidity {
  bool negative_moment = false;  ///< inertia-not-positive-definite
  bool triangle = false;         ///< inertia-triangle: A + B < C
  double triangle_margin = 0;    ///< A + B - C of the sorted moments
  bool valid() const { return !negative_moment && !triangle; }
};
InertiaValidity inertia_validity(const PrincipalInertia& principal);

/// The one inertia-balancing function. Returns nullopt when the tensor is valid as it is.
/// Otherwise the nearest valid tensor: negative principal moments are clamped to 0, then the
/// moments are projected orthogonally onto A + B - C = s with s = 1e-7·(A + B + C) so that
/// rounding in any consumer keeps it valid (when that would pass the two largest
/// moments, they meet at their mean and the smallest becomes s); the principal axes are kept. This is the smallest
/// change to the moments (Euclidean), which is why it is used rather than MuJoCo's
/// `balanceinertia` (every moment replaced by their mean). An all-zero result stays nullopt.
std::optional<Eigen::Matrix3d> balance_inertia(const Eigen::Matrix3d& inertia);

}  // namespace bodyfmt
#pragma GCC visibility pop
