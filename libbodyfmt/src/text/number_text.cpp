#include "text/number_text.h"

#include <charconv>
#include <cstdlib>

namespace bodyfmt::detail {

bool is_yaml_special_float(std::string_view text) {
  if (!text.empty() && (text.front() == '+' || text.front() == '-')) text.remove_prefix(1);
  for (std::string_view word : {".nan", ".NaN", ".NAN", ".inf", ".Inf", ".INF"})
    if (text == word) return true;
  return false;
}

bool only_trailing_space(const char* p) {
  while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') ++p;
  return *p == '\0';
}

std::optional<double> parse_plain_decimal(std::string_view text) {
  // from_chars reads the decimal forms strtod reads, without the sign '+', leading blanks,
  // hexadecimal, inf and nan; only a text that starts like a decimal number and is read whole
  // and in range is taken, so it means what strtod makes of it: both round correctly.
  const char* p = text.data();
  const char* const end = p + text.size();
  const char* digits = p != end && *p == '-' ? p + 1 : p;
  if (digits != end && *digits == '.') ++digits;
  if (digits == end || *digits < '0' || *digits > '9') return std::nullopt;
  double value = 0;
  const auto [stop, error] = std::from_chars(p, end, value);
  if (error != std::errc() || stop != end) return std::nullopt;
  return value;
}

std::optional<double> parse_double_exact(std::string_view text) {
  if (auto value = parse_plain_decimal(text)) return value;
  if (text.empty()) return std::nullopt;
  const char* begin = text.data();
  char* end = nullptr;
  double value = std::strtod(begin, &end);
  if (end == begin || !only_trailing_space(end)) return std::nullopt;
  return value;
}

}  // namespace bodyfmt::detail
