#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/model.h>

#include <fmt/format.h>

namespace bodyfmt::converters {

std::string format_number(double value) {
  if (value == 0) return "0";  // also -0
  return fmt::format("{}", value);
}

std::string format_vector(const Eigen::Vector3d& v) {
  return format_number(v.x()) + ' ' + format_number(v.y()) + ' ' + format_number(v.z());
}

std::string format_vector(const Eigen::Vector4d& v) {
  return format_number(v[0]) + ' ' + format_number(v[1]) + ' ' + format_number(v[2]) + ' ' + format_number(v[3]);
}

double finite_or_stand_in(double value) {
  if (value >= kUnlimited) return kUnlimitedStandIn;
  if (value <= -kUnlimited) return -kUnlimitedStandIn;
  return value;
}

}  // namespace bodyfmt::converters
