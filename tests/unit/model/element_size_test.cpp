// The per-link model elements of a large model (issue 14: bodycheck at <= 1.5 KB per link on
// a 100,000-link chain). Bounds for 64-bit libstdc++ with Eigen's 16-byte alignment; a new
// member that crosses one should be held on the heap when most links leave it unset.

#include <bodyfmt/derived.h>
#include <bodyfmt/model.h>

#include <doctest/doctest.h>

using namespace bodyfmt;

TEST_CASE("per-link model elements stay within their byte budgets" * doctest::skip(sizeof(void*) != 8)) {
  CHECK(sizeof(Link) <= 480);
  CHECK(sizeof(LinkSources) <= 112);
  CHECK(sizeof(Shape) <= 192);
  CHECK(sizeof(Geometry) <= 32);
  CHECK(sizeof(SceneFrame) <= 112);
  CHECK(sizeof(MassContribution) <= 120);
  CHECK(sizeof(Derived::X_WL[0]) <= 96);
}
