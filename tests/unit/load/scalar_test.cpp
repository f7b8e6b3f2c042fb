// Loader unit tests for load/scalar.cpp: "required" (lenient strtod) and "optional" (whole
// scalar or default) conversions, body-format-spec §1.2.

#include "load/scalar.h"
#include "support/load_helpers.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

using bodyfmt::test::load_v2;
using bodyfmt::test::Pos;
using bodyfmt::test::pos;

TEST_CASE("load: 0.t in a required number reads 0 with load-lenient-number") {
  auto r = load_v2(R"(
links:
  - name: A
    translation: [0.t, 1, 2]
)");
  auto d = r.take("load-lenient-number");
  CHECK(d.severity == bodyfmt::Severity::kWarning);
  CHECK(pos(d) == Pos{5, 19});
  CHECK(r.link("A").X_PL.translation() == Eigen::Vector3d(0, 1, 2));
  r.expect_clean();
}

TEST_CASE("load: 1.5kg as link mass reads 1.5 with load-lenient-number") {
  auto r = load_v2(R"(
links:
  - name: A
    mass: 1.5kg
)");
  CHECK(pos(r.take("load-lenient-number")) == Pos{5, 11});
  const auto& c = r.link("A").mass_contributions;
  REQUIRE(c.size() == 1);
  CHECK(c[0].mass == 1.5);
  r.expect_clean();
}

TEST_CASE("load: a required number with no numeric prefix is load-number") {
  auto r = load_v2(R"(
links:
  - name: A
    translation: [x, 1, 2]
)");
  auto d = r.take("load-number");
  CHECK(d.severity == bodyfmt::Severity::kError);
  CHECK(pos(d) == Pos{5, 19});
  CHECK(r.link("A").X_PL.translation() == Eigen::Vector3d::Zero());
  r.expect_clean();
}

TEST_CASE("load: an optional number that does not parse keeps the default (radius: abc)") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Sphere, radius: abc}
)");
  auto d = r.take("load-ignored-value");
  CHECK(d.severity == bodyfmt::Severity::kWarning);
  // "        geometry: {type: Sphere, radius: " is 41 characters.
  CHECK(pos(d) == Pos{7, 42});
  const auto& shapes = r.link("A").shapes;
  REQUIRE(shapes.size() == 1);
  CHECK(std::get<bodyfmt::Sphere>(shapes[0].geometry).radius == 1.0);
  r.expect_clean();
}

TEST_CASE("load: an optional number is the whole scalar: 0.5m is ignored, not 0.5") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Sphere, radius: 0.5m}
)");
  CHECK(pos(r.take("load-ignored-value")) == Pos{7, 42});
  CHECK(std::get<bodyfmt::Sphere>(r.link("A").shapes.at(0).geometry).radius == 1.0);
  r.expect_clean();
}

TEST_CASE("load: optional booleans accept exactly the YAML 1.1 spellings") {
  auto r = load_v2(R"(
links:
  - name: A
    elements:
      - type: Shape
        geometry: {type: Cylinder, top: off, bottom: No}
      - type: Shape
        geometry: {type: Cylinder, top: nope}
)");
  const auto& shapes = r.link("A").shapes;
  REQUIRE(shapes.size() == 2);
  const auto& c0 = std::get<bodyfmt::Cylinder>(shapes[0].geometry);
  CHECK_FALSE(c0.top);
  CHECK_FALSE(c0.bottom);
  // "        geometry: {type: Cylinder, top: " is 40 characters.
  CHECK(pos(r.take("load-ignored-value")) == Pos{9, 41});
  CHECK(std::get<bodyfmt::Cylinder>(shapes[1].geometry).top);
  r.expect_clean();
}

TEST_CASE("parse_plain_decimal: the value strtod reads, bit for bit, or nothing") {
  using bodyfmt::detail::parse_plain_decimal;
  auto same_as_strtod = [](const std::string& text) {
    auto fast = parse_plain_decimal(text);
    if (!fast) return true;
    char* end = nullptr;
    const double slow = std::strtod(text.c_str(), &end);
    return *end == '\0' && std::memcmp(&slow, &*fast, sizeof slow) == 0;
  };
  // Taken: whole decimal numbers.
  for (const char* text :
       {"0", "-0", "1", "0.1", "-0.25", ".5", "-.5", "5.", "1e-3", "1E+300", "007", "2.2250738585072014e-308",
        "0.30000000000000004", "123456789012345678901234567890", "4.9406564584124654e-324", "1.7976931348623157e308"}) {
    CAPTURE(text);
    CHECK(parse_plain_decimal(text).has_value());
    CHECK(same_as_strtod(text));
  }
  CHECK(std::signbit(*parse_plain_decimal("-0")));
  // Left to strtod and the diagnostics: signs, blanks, other spellings, junk, overflow.
  for (const char* text : {"",     "-",     ".",      "-.", "+1",    " 1",  "1 ",    "0x10",  "inf", "-inf", "nan",
                           ".inf", "1e999", "-1e999", "1e", "1.5kg", "0.t", "2.0.1", "1_000", "e5",  "--1"}) {
    CAPTURE(text);
    CHECK_FALSE(parse_plain_decimal(text).has_value());
  }
  // Random decimals across the whole range, subnormals and roundings included.
  std::mt19937_64 random(20261123);
  int taken = 0;
  for (int i = 0; i < 200000; ++i) {
    std::string text = random() % 4 == 0 ? "-" : "";
    const int digits = 1 + static_cast<int>(random() % 25);
    const int point = static_cast<int>(random() % (digits + 1));
    for (int d = 0; d < digits; ++d) {
      if (d == point) text += '.';
      text += static_cast<char>('0' + random() % 10);
    }
    if (random() % 2 == 0) text += "e" + std::to_string(static_cast<int>(random() % 660) - 340);
    if (parse_plain_decimal(text)) ++taken;
    if (!same_as_strtod(text)) FAIL_CHECK(text);
  }
  CHECK(taken > 190000);  // only out-of-range exponents fall back
}
