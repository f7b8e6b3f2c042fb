#pragma once
/// Number formatting for text formats: shortest round-trip decimal ({fmt}'s "{}"), so that a
/// parser reads back exactly the same double, and never "-0".
#include <Eigen/Core>

#include <string>

namespace bodyfmt::converters {

/// Written for limits Choreonoid leaves unlimited where a format requires a number (URDF's
/// `effort` and `velocity`, a one-sided range). Large enough to never bind, small enough for
/// float-based tools.
constexpr double kUnlimitedStandIn = 1e30;

/// `value`, or ±kUnlimitedStandIn where it is Choreonoid's ±unlimited (model.h kUnlimited).
double finite_or_stand_in(double value);

std::string format_number(double value);
/// "x y z" with format_number for each.
std::string format_vector(const Eigen::Vector3d& v);
/// "a b c d" (rgba and the like).
std::string format_vector(const Eigen::Vector4d& v);

}  // namespace bodyfmt::converters
