// Findings inside text shared through an alias point at the text and name the alias use that
// led to it; text read through several aliases is reported once.

#include <doctest/doctest.h>

#include "support/load_helpers.h"

using bodyfmt::test::load_v2;
using bodyfmt::test::pos;
using bodyfmt::test::Pos;

TEST_CASE("load: a finding inside an aliased mapping names the alias use as via") {
  auto r = load_v2(R"(
shapes:
  ball: &BALL
    type: Shape
    geometry: { type: Sphere, radius: abc }
links:
  - name: A
    elements:
      - *BALL
)");
  r.drop_notes("load-info-key");
  auto d = r.take("load-ignored-value");
  CHECK(pos(d) == Pos{6, 39});  // the text
  REQUIRE(d.via.has_value());
  CHECK(pos(*d.via) == Pos{10, 9});  // the alias use
  r.expect_clean();
}

TEST_CASE("load: a problem in text used through several aliases is reported once") {
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
  - name: C
    parent: A
    elements:
      - *BALL
)");
  auto d = r.take("load-ignored-value");
  CHECK(pos(d) == Pos{8, 43});
  CHECK_FALSE(r.has("load-ignored-value"));
  r.expect_clean();
}
