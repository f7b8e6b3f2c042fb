#include "number_options.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <string>

namespace bodyfmt::tools {

namespace {

/// The whole text as a finite number (nan, inf and 1e999 are not), or nothing.
std::optional<double> parse_finite(const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

CLI::Validator whole_number_above_zero() {
  return CLI::Validator(
      [](const std::string& value) {
        std::size_t used = 0;
        long long n = 0;
        try {
          n = std::stoll(value, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        return used == value.size() && n > 0 ? std::string() : "must be a whole number above 0, not " + value;
      },
      "N > 0");
}

CLI::Validator number_above_zero(bool or_equal) {
  return CLI::Validator(
      [or_equal](const std::string& text) {
        const std::optional<double> value = parse_finite(text);
        const bool ok = value && (or_equal ? *value >= 0 : *value > 0);
        return ok ? std::string() : std::string("must be a number ") + (or_equal ? "≥" : "above") + " 0, not " + text;
      },
      or_equal ? "NONNEGATIVE" : "POSITIVE");
}

CLI::Validator finite_number_in(double low, double high) {
  std::ostringstream range;
  range << low << " to " << high;
  return CLI::Validator(
      [low, high, range = range.str()](const std::string& text) {
        const std::optional<double> value = parse_finite(text);
        const bool ok = value && *value >= low && *value <= high;
        return ok ? std::string() : "must be a number from " + range + ", not " + text;
      },
      "NUMBER in [" + range.str() + "]");
}

}  // namespace bodyfmt::tools
