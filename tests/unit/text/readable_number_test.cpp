// Numbers in messages as a person reads them (issue 47): not the digits float arithmetic leaves.
#include <bodyfmt/readable_number.h>

#include <doctest/doctest.h>

#include "support/run_command.h"

#include <cmath>
#include <limits>
#include <string>

using bodyfmt::readable_number;

TEST_CASE("readable_number: six significant digits, no trailing zeros, no -0") {
  CHECK(readable_number(0.45 * 0.3 * 0.1 * 1000) == "13.5");  // 13.500000000000002 in full
  CHECK(readable_number(0.1 + 0.2) == "0.3");
  CHECK(readable_number(1.0 / 3) == "0.333333");
  CHECK(readable_number(8) == "8");
  CHECK(readable_number(-0.0) == "0");
  CHECK(readable_number(1e-7) == "1e-07");
  CHECK(readable_number(123456789) == "1.23457e+08");
  CHECK(readable_number(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(readable_number(std::nan("")) == "nan");
}

// bodyinfo --mass-from-geometry for people: the hull box 0.45 x 0.3 x 0.1 at 1000 kg/m³ is 13.5 kg,
// and the tensors have no 1e-18 left over from turning the gun (a zero is written 0).
TEST_CASE("bodyinfo --mass-from-geometry prints numbers as a person reads them") {
  const auto run = bodyfmt::test::run_command(std::string(BODYFMT_BODYINFO) + " --mass-from-geometry '" +
                                              BODYFMT_EXAMPLES_DIR + "/simpletank.body'");
  CHECK(run.status == 0);
  CHECK(run.output.find("  mass               8 | 13.5\n") != std::string::npos);
  CHECK(run.output.find("0000000") == std::string::npos);
  CHECK(run.output.find("e-1") == std::string::npos);
  CHECK(run.output.find("e-2") == std::string::npos);
  // The turret's written tensor, diag(0.2, 0.14, 0.23) with the gun's rounding off the diagonal.
  CHECK(run.output.find("  inertia            [0.2, 0, 0, 0, 0.14, 0, 0, 0, 0.23] | ") != std::string::npos);
}
