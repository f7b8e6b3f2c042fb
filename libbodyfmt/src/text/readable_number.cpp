#include <bodyfmt/readable_number.h>

#include <fmt/format.h>

namespace bodyfmt {

std::string readable_number(double value) {
  if (value == 0) return "0";  // also -0
  return fmt::format("{:.6g}", value);
}

}  // namespace bodyfmt
