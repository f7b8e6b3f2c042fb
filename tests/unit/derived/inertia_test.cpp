// The one inertia unit (bodyfmt/inertia.h): principal moments, validity and balancing.
#include <bodyfmt/inertia.h>

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <random>

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

TEST_CASE("inertia: symmetrising a tensor of finite entries near DBL_MAX keeps it finite") {
  // fuzz_mjcf: (1e308 + 1e308) / 2 was infinite, and the balanced tensor written was NaN.
  Matrix3d I = Vector3d(1e308, 0.0042, 0.0036).asDiagonal();
  I(1, 2) = 1.7e308;
  I(2, 1) = 1.7e308;
  CHECK(symmetrized_inertia(I).allFinite());
  CHECK(symmetrized_inertia(I)(0, 0) == 1e308);
  CHECK(symmetrized_inertia(I)(1, 2) == 1.7e308);
  CHECK(principal_inertia(Vector3d(1e308, 0.0042, 0.0036).asDiagonal()).moments[2] == 1e308);
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
  // (0, 0.3, 0.3) after clamping sits on A + B = C; the margin s = 1e-7 * 0.6 goes to the
  // smallest moment, the two equal ones stay put.
  CHECK((*balanced)(0, 0) == doctest::Approx(6e-8).epsilon(1e-9));
  CHECK((*balanced)(1, 1) == doctest::Approx(0.3).epsilon(1e-15));
  CHECK((*balanced)(2, 2) == doctest::Approx(0.3).epsilon(1e-15));
  CHECK(inertia_validity(principal_inertia(Vector3d(-0.1, 0.3, 0.3).asDiagonal())).negative_moment);
}

TEST_CASE("inertia: a balanced tensor satisfies the triangle inequality after its own eigendecomposition") {
  // MuJoCo re-derives principal moments from what is written and checks A + B >= C with no
  // tolerance, so the balanced tensor must keep a positive margin through rounding. The
  // rotated (-1, 1, 1) case (two largest moments equal) once came out as (6.7e-8, 1 - 6.7e-8,
  // 1 + 6.7e-8): found by fuzz_mjcf.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> moment(-1.0, 1.0);
  int balanced_count = 0;
  for (int i = 0; i < 2000; ++i) {
    const Matrix3d R =
        Eigen::Quaterniond(Eigen::Vector4d(moment(random), moment(random), moment(random), moment(random)).normalized())
            .toRotationMatrix();
    Vector3d m(moment(random), moment(random), moment(random));
    if (i % 3 == 0) m[2] = m[1];  // ties, as in (-1, 1, 1)
    const Matrix3d I = R * m.asDiagonal() * R.transpose();
    const auto balanced = balance_inertia(I);
    if (!balanced) continue;
    ++balanced_count;
    const PrincipalInertia p = principal_inertia(*balanced);
    INFO("moments in: " << m.transpose() << "  out: " << p.moments.transpose());
    REQUIRE(p.moments[0] >= 0);
    REQUIRE(p.moments[0] + p.moments[1] - p.moments[2] > 0);
  }
  CHECK(balanced_count > 1000);
  const auto fuzz_case = balance_inertia((Matrix3d() << 0, 1, 0, 1, 0, 0, 0, 0, 1).finished());
  REQUIRE(fuzz_case);
  const Vector3d out = principal_inertia(*fuzz_case).moments;
  CHECK(out[1] == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(out[2] == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(out[0] == doctest::Approx(2e-7).epsilon(1e-6));
}
