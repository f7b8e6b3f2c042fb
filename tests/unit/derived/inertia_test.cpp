// The one inertia unit (bodyfmt/inertia.h): principal moments, validity and balancing.
#include <bodyfmt/inertia.h>

#include <doctest/doctest.h>

#include <Eigen/Geometry>

using namespace bodyfmt;
using Eigen::Matrix3d;
using Eigen::Vector3d;

TEST_CASE("inertia: a diagonal tensor's moments are read exactly, sorted, with their axes") {
  const PrincipalInertia p = principal_inertia(Vector3d(0.5, 0.1, 0.3).asDiagonal());
  CHECK(p.exact);
  CHECK(p.moments == Vector3d(0.1, 0.3, 0.5));
  CHECK(p.axes.col(0) == Vector3d(0, 1, 0));
  CHECK(p.axes.col(2) == Vector3d(1, 0, 0));
}

TEST_CASE("inertia: the symmetrised tensor is (I + Iᵀ)/2") {
  Matrix3d I;
  I << 1, 0.2, 0, 0, 1, 0, 0, 0, 1;
  CHECK(symmetrized_inertia(I)(0, 1) == 0.1);
  CHECK(symmetrized_inertia(I)(1, 0) == 0.1);
}

TEST_CASE("inertia: a valid tensor needs no balancing") {
  CHECK_FALSE(balance_inertia(Vector3d(0.2, 0.2, 0.4).asDiagonal()).has_value());  // A + B = C exactly
  CHECK_FALSE(balance_inertia(Matrix3d::Identity()).has_value());
  CHECK(inertia_validity(principal_inertia(Vector3d(0.2, 0.2, 0.4).asDiagonal())).valid());
}

TEST_CASE("inertia: SimpleTank's chassis diag(0.1, 0.1, 0.5) is projected onto A + B - C = s") {
  // Excess 0.3 and s = 1e-7·0.7: each moment moves by t = (0.3 + 7e-8)/3 toward the plane,
  // (0.1, 0.1, 0.5) -> (0.2 + 2.33e-8, 0.2 + 2.33e-8, 0.4 - 2.33e-8).
  const Matrix3d chassis = Vector3d(0.1, 0.1, 0.5).asDiagonal();
  const InertiaValidity before = inertia_validity(principal_inertia(chassis));
  CHECK(before.triangle);
  CHECK(before.triangle_margin == doctest::Approx(-0.3).epsilon(1e-15));
  const auto balanced = balance_inertia(chassis);
  REQUIRE(balanced);
  const double t = (0.3 + 1e-7 * 0.7) / 3;
  CHECK((*balanced)(0, 0) == doctest::Approx(0.1 + t).epsilon(1e-14));
  CHECK((*balanced)(1, 1) == doctest::Approx(0.1 + t).epsilon(1e-14));
  CHECK((*balanced)(2, 2) == doctest::Approx(0.5 - t).epsilon(1e-14));
  const PrincipalInertia after = principal_inertia(*balanced);
  CHECK(after.moments[0] + after.moments[1] - after.moments[2] == doctest::Approx(7e-8).epsilon(1e-6));
  CHECK(inertia_validity(after).valid());
}

TEST_CASE("inertia: balancing keeps the principal axes of a rotated tensor") {
  const Matrix3d R = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Matrix3d I = R * Vector3d(0.1, 0.2, 0.9).asDiagonal() * R.transpose();
  const auto balanced = balance_inertia(I);
  REQUIRE(balanced);
  const Matrix3d in_axes = R.transpose() * *balanced * R;
  CHECK(std::abs(in_axes(0, 1)) < 1e-12);
  CHECK(std::abs(in_axes(0, 2)) < 1e-12);
  CHECK(std::abs(in_axes(1, 2)) < 1e-12);
  // Excess 0.6: t = (0.6 + 1.2e-7)/3 = 0.2 + 4e-8.
  CHECK(in_axes(2, 2) == doctest::Approx(0.7 - 4e-8).epsilon(1e-12));
}

TEST_CASE("inertia: negative principal moments are clamped to zero first") {
  const auto balanced = balance_inertia(Vector3d(-0.1, 0.3, 0.3).asDiagonal());
  REQUIRE(balanced);
  CHECK((*balanced)(0, 0) == 0.0);
  CHECK((*balanced)(1, 1) == 0.3);
  CHECK((*balanced)(2, 2) == 0.3);
  CHECK(inertia_validity(principal_inertia(Vector3d(-0.1, 0.3, 0.3).asDiagonal())).negative_moment);
}
