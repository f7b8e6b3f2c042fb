#include "fields/field_text.h"

#include <bodyfmt/angles.h>

#include <fmt/format.h>

#include <cmath>

namespace bodyfmt::detail {
namespace {

constexpr double kDegree = 180.0 / kPi;

std::string number_text(double x, int precision) {
  if (x == kUnlimited) return "unlimited";
  if (x == -kUnlimited) return "-unlimited";
  // -0, and the rounding noise of a cancelled sum (far below any tolerance), read as 0
  if (std::abs(x) < 1e-15) return "0";
  if (precision > 0) {
    std::string s = fmt::format("{:.{}g}", x, precision);
    return s == "-0" ? "0" : s;
  }
  return fmt::format("{}", x);
}

std::string list_text(const double* x, std::size_t n, int precision) {
  std::string out = "[";
  for (std::size_t i = 0; i < n; ++i) out += (i ? ", " : "") + number_text(x[i], precision);
  return out + "]";
}

// Choreonoid's roll-pitch-yaw (R = Rz(yaw) Ry(pitch) Rx(roll)), in degrees.
Eigen::Vector3d rpy_degrees(const Eigen::Matrix3d& R) {
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  double roll, yaw;
  if (std::abs(std::cos(pitch)) > 1e-12) {
    roll = std::atan2(R(2, 1), R(2, 2));
    yaw = std::atan2(R(1, 0), R(0, 0));
  } else {
    roll = 0;
    yaw = std::atan2(-R(0, 1), R(1, 1));
  }
  Eigen::Vector3d rpy = Eigen::Vector3d(roll, pitch, yaw) * kDegree;
  for (double& a : rpy)
    if (std::abs(a) < 1e-9) a = 0;  // rounding noise of a composed rotation, not an angle
  return rpy;
}

}  // namespace

std::string field_value(const Field& field, int precision) {
  const std::vector<double>& n = field.numbers;
  std::string numbers;
  switch (field.style) {
    case FieldStyle::kText: return field.text;
    case FieldStyle::kNumber:
      if (n.size() > 12 && !field.text.empty()) return field.text;  // a mesh's numbers
      numbers = n.size() == 1 ? number_text(n[0], precision) : list_text(n.data(), n.size(), precision);
      break;
    case FieldStyle::kVector:
    case FieldStyle::kRange: numbers = list_text(n.data(), n.size(), precision); break;
    case FieldStyle::kAngleRange: {
      // The file writes degrees (format 2.0 and most 1.0 files): show them beside the radians.
      const double degrees[] = {std::abs(n[0]) == kUnlimited ? n[0] : n[0] * kDegree,
                                std::abs(n[1]) == kUnlimited ? n[1] : n[1] * kDegree};
      numbers = list_text(n.data(), n.size(), precision) + " rad = " + list_text(degrees, 2, 12) + " deg";
      break;
    }
    case FieldStyle::kRotation:
    case FieldStyle::kPose:
    case FieldStyle::kAffine: {
      Eigen::Matrix3d R;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) R(r, c) = n[3 + 3 * r + c];
      const bool rigid = (R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0;
      const bool translated = field.style != FieldStyle::kRotation;
      if (translated) numbers = "xyz " + list_text(n.data(), 3, precision);
      if (rigid) {
        const Eigen::Vector3d rpy = rpy_degrees(R);
        numbers +=
            (translated ? " rpy " : "rpy ") + list_text(rpy.data(), 3, precision > 0 ? precision - 3 : 0) + " deg";
      } else {
        numbers += " linear " + list_text(n.data() + 3, 9, precision);
      }
      break;
    }
    case FieldStyle::kBox:
      numbers = "min " + list_text(n.data(), 3, precision) + " max " + list_text(n.data() + 3, 3, precision);
      break;
    case FieldStyle::kInertia: {
      const double six[] = {n[0], n[3], n[6], n[4], n[7], n[8]};
      numbers = list_text(six, 6, precision);
      break;
    }
  }
  return field.text.empty() ? numbers : field.text + " " + numbers;
}

}  // namespace bodyfmt::detail
