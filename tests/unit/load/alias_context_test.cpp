// Findings inside text shared through an alias point at the text and name the alias use that
// led to it, so that a user can tell which of several uses is meant.

#include <doctest/doctest.h>

#include "support/load_helpers.h"

using bodyfmt::test::load_v2;
using bodyfmt::test::pos;
using bodyfmt::test::Pos;

TEST_CASE("load: a finding inside an aliased mapping names the alias use as via") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - &BALL
        type: Shape
        geometry: { type: Sphere, radius: abc }
  - name: B
    parent: A
    elements:
      - *BALL
)");
  // The first read is the anchor's own use: no alias involved.
  auto first = r.take("load-ignored-value");
  CHECK(pos(first) == Pos{8, 43});
  CHECK_FALSE(first.via.has_value());
  // The second comes through `*BALL` on line 12.
  auto second = r.take("load-ignored-value");
  CHECK(pos(second) == Pos{8, 43});
  REQUIRE(second.via.has_value());
  CHECK(pos(*second.via) == Pos{12, 9});
  r.expect_clean();
}
