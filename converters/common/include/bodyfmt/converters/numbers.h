#pragma once
/// Number formatting for text formats: shortest round-trip decimal ({fmt}'s "{}"), so that a
/// parser reads back exactly the same double, and never "-0".
#include <Eigen/Core>

#include <string>

namespace bodyfmt::converters {

std::string format_number(double value);
/// "x y z" with format_number for each.
std::string format_vector(const Eigen::Vector3d& v);
/// "a b c d" (rgba and the like).
std::string format_vector(const Eigen::Vector4d& v);

}  // namespace bodyfmt::converters
