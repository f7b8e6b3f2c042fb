#pragma once
/// Validators for numeric options that state their bound in words. CLI11's PositiveNumber prints
/// its range as a 300-digit double and calls 0 "not in range 0 to ..."; a limit of 0 or less
/// would switch its guard off, so it is a usage error said plainly.

#include <CLI/CLI.hpp>

namespace bodyfmt::tools {

/// A whole number above 0 ("must be a whole number above 0, not X"); the type name "N > 0".
CLI::Validator whole_number_above_zero();

/// A finite number above 0, or at least 0 when `or_equal` ("must be a number above 0, not X",
/// "must be a number ≥ 0, not X"); the type names POSITIVE and NONNEGATIVE.
CLI::Validator number_above_zero(bool or_equal);

/// A finite number from `low` to `high` ("must be a number from LOW to HIGH, not X"). CLI11's
/// Range lets nan through (every comparison with it is false), and bodysim hands a nan accuracy
/// to Simbody, which aborts; the type name "NUMBER in [LOW, HIGH]".
CLI::Validator finite_number_in(double low, double high);

}  // namespace bodyfmt::tools
