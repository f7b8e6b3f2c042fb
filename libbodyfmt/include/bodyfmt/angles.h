#pragma once
/// π, defined once for the whole project: C++17 has no std::numbers, and M_PI is a POSIX
/// extension that strict compilers leave out.

#include <bodyfmt/export.h>

#pragma GCC visibility push(default)
namespace bodyfmt {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace bodyfmt
#pragma GCC visibility pop
