#pragma once
/// When an angle looks written in the other unit (body-format-spec §3): the thresholds that the
/// loader's units-*-looks-degree and units-rotation-looks-radian findings and the validator's
/// units-range-looks-radian share, in one place. Values are as written, in the file's unit.

#include <bodyfmt/angles.h>
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <cmath>
#include <initializer_list>

#pragma GCC visibility push(default)
namespace bodyfmt::units {

/// How close (absolute, in the written number) a value must be to k·π/12 to look like radians.
/// 3.14 is 0.0016 from π and 1.57 is 0.0008 from π/2; integer degrees 1..6 are at least 0.026
/// from any multiple of π/12, so legitimate small degree values never match.
inline constexpr double kRadianMatch = 0.002;

/// The k of k·π/12 (k = 1..24, so up to a full turn) that |written| is within kRadianMatch of,
/// or 0.
inline int pi_twelfths(double written) {
  const double a = std::abs(written);
  for (int k = 1; k <= 24; ++k)
    if (std::abs(a - k * kPi / 12) <= kRadianMatch) return k;
  return 0;
}

/// One turn each way, a joint range's limit in a radian file.
inline constexpr double kRangeTurn = 2 * kPi + kRadianMatch;
/// 8 turns a second (480 rpm) at the joint, a velocity limit in rad/s.
inline constexpr double kVelocityTurns = 16 * kPi;
/// Degrees are written as round numbers up to a turn (3600 deg/s for velocities).
inline constexpr double kMostDegrees = 360 + kRadianMatch;
inline constexpr double kMostDegreesPerSecond = 3600 + kRadianMatch;

/// A multiple of 0.5, as degrees are written.
inline bool round_degrees(double w) { return std::abs(w * 2 - std::round(w * 2)) < 1e-9; }

/// The finite values of `values` (±kUnlimited is unlimited) look like degrees in a radian file:
/// one beyond `threshold`, none beyond `most`, every one beyond `threshold` a multiple of 0.5.
/// Radians beyond a turn are rare and never round.
inline bool looks_like_degrees(std::initializer_list<double> values, double threshold, double most) {
  bool beyond = false;
  for (double v : values) {
    if (std::abs(v) >= kUnlimited) continue;
    if (std::abs(v) > most) return false;
    if (std::abs(v) <= threshold) continue;
    if (!round_degrees(v)) return false;
    beyond = true;
  }
  return beyond;
}

/// A revolute joint range in a radian file that looks like degrees ([-90, 90]).
inline bool range_looks_like_degrees(double lower, double upper) {
  return looks_like_degrees({lower, upper}, kRangeTurn, kMostDegrees);
}
/// A revolute velocity limit in rad/s that looks like deg/s (180).
inline bool velocity_looks_like_degrees(double lower, double upper) {
  return looks_like_degrees({lower, upper}, kVelocityTurns, kMostDegreesPerSecond);
}

/// A rotation angle in a degree file that looks like radians: non-zero, within a turn, and within
/// kRadianMatch of k·π/12 (1.5708, 3.1416, 0.7854...). The joint range rule's second test (all
/// within π and none whole) is left out: a single small tilt (2.35, 0.2 degrees) is common.
inline bool rotation_looks_like_radians(double written) { return pi_twelfths(written) > 0; }

}  // namespace bodyfmt::units
#pragma GCC visibility pop
