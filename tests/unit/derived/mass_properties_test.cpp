// compute_mass_properties (body-format-spec §6.4), with values derived by hand.
#include <bodyfmt/derived.h>

#include <doctest/doctest.h>

using namespace bodyfmt;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

MassContribution contribution(double mass, Vector3d com, Vector3d diagonal) {
  MassContribution c;
  c.mass = mass;
  c.center_of_mass = com;
  c.inertia = diagonal.asDiagonal();
  return c;
}

}  // namespace

TEST_CASE("derived: a link without mass data gets Choreonoid's defaults (1 kg, origin, identity)") {
  const MassProperties mp = compute_mass_properties(Link{});
  CHECK(mp.mass == 1.0);
  CHECK(mp.center_of_mass.isZero(0));
  CHECK(mp.inertia.isIdentity(0));
}

TEST_CASE("derived: two bodies combine by the parallel-axis theorem about their common CoM") {
  // 2 kg at x = +1 and 2 kg at x = -1, each diag(0.1, 0.2, 0.3): the CoM is the origin and each
  // adds m (|d|² I - d dᵀ) = 2 diag(0, 1, 1), so I = diag(0.2, 4.4, 4.6).
  Link link;
  link.mass_contributions = {contribution(2, {1, 0, 0}, {0.1, 0.2, 0.3}), contribution(2, {-1, 0, 0}, {0.1, 0.2, 0.3})};
  const MassProperties mp = compute_mass_properties(link);
  CHECK(mp.mass == 4.0);
  CHECK(mp.center_of_mass.isZero(1e-15));
  CHECK((mp.inertia - Vector3d(0.2, 4.4, 4.6).asDiagonal().toDenseMatrix()).cwiseAbs().maxCoeff() < 1e-15);
}

TEST_CASE("derived: unequal masses put the CoM at the weighted mean and shift by the offsets") {
  // 3 kg at (0, 0, 0) and 1 kg at (0, 0, 4): CoM z = 1; offsets -1 and +3 along z give
  // 3·1·diag(1, 1, 0) + 1·9·diag(1, 1, 0) = diag(12, 12, 0) on top of the own inertias.
  Link link;
  link.mass_contributions = {contribution(3, {0, 0, 0}, {1, 1, 1}), contribution(1, {0, 0, 4}, {0, 0, 0})};
  const MassProperties mp = compute_mass_properties(link);
  CHECK(mp.mass == 4.0);
  CHECK(mp.center_of_mass.isApprox(Vector3d(0, 0, 1)));
  CHECK(mp.inertia.isApprox(Vector3d(13, 13, 1).asDiagonal().toDenseMatrix()));
}

TEST_CASE("derived: a massless combination drops the individual inertias (§6.4 rule 3)") {
  Link link;
  link.mass_contributions = {contribution(0, {1, 2, 3}, {0.5, 0.5, 0.5})};
  const MassProperties mp = compute_mass_properties(link);
  CHECK(mp.mass == 0.0);
  CHECK(mp.center_of_mass.isZero(0));
  CHECK(mp.inertia.isZero(0));
}
