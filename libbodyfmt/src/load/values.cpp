#include "load/values.h"

#include <bodyfmt/model.h>

#include "load/scalar.h"
#include "load/unit_checks.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>
#include <utility>
#include <vector>

namespace bodyfmt::detail {
namespace {

bool expect_sequence(LoadContext& ctx, const yaml::NodeRef& ref, const char* what) {
  if (ref && ref->is_sequence()) return true;
  ctx.report("load-type", ref, std::string(what) + " must be a sequence");
  return false;
}

bool is_sequence_of_sequences(const yaml::NodeRef& ref) {
  return ref && ref->is_sequence() && !ref->items().empty() && ref->items().front()->is_sequence();
}

}  // namespace

namespace {

// Reads the `size` numbers of sequence `ref` into `out` (the caller checked the size); false
// at the first one that fails, which is reported. No heap: a link reads several of these.
bool read_items(LoadContext& ctx, const yaml::NodeRef& ref, double* out) {
  for (const yaml::NodeRef& item : ref->items()) {
    auto x = required_double(ctx, ref.child(item));
    if (!x) return false;
    *out++ = *x;
  }
  return true;
}

bool has_size(LoadContext& ctx, const yaml::NodeRef& ref, int size) {
  if (!expect_sequence(ctx, ref, "this value")) return false;
  if (static_cast<int>(ref->items().size()) == size) return true;
  ctx.report("load-vector-size", ref,
             "a " + std::to_string(size) + "-element vector is expected, found " + std::to_string(ref->items().size()) +
                 " elements");
  return false;
}

}  // namespace

std::optional<Eigen::VectorXd> read_vector(LoadContext& ctx, const yaml::NodeRef& ref, int size) {
  if (!has_size(ctx, ref, size)) return std::nullopt;
  Eigen::VectorXd v(size);
  if (!read_items(ctx, ref, v.data())) return std::nullopt;
  return v;
}

std::optional<Eigen::Vector3d> read_vec3(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!has_size(ctx, ref, 3)) return std::nullopt;
  Eigen::Vector3d v;
  if (!read_items(ctx, ref, v.data())) return std::nullopt;
  return v;
}

std::optional<Eigen::Vector3d> read_optional_vec3(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (ref && !ref->is_sequence()) {
    // body-format-spec §1.2: `size: 1` is silently treated as absent by Choreonoid.
    ctx.report("load-ignored-value", ref,
               "this value must be a 3-element sequence; Choreonoid ignores it and uses the default",
               "write [x, y, z]");
    return std::nullopt;
  }
  return read_vec3(ctx, ref);
}

namespace {

bool of_type_or_ignored(LoadContext& ctx, const yaml::NodeRef& ref, std::string_view key, bool is_expected,
                        const char* expected) {
  if (is_expected) return true;
  ctx.report("load-ignored-value", ref,
             std::string(key) + (ref->is_null() ? " is empty" : " must be a " + std::string(expected)) +
                 "; Choreonoid skips it without a word",
             ref->is_null() ? "give it a value or remove the key" : std::string("write a ") + expected);
  return false;
}

}  // namespace

bool listing_or_ignored(LoadContext& ctx, const yaml::NodeRef& ref, std::string_view key) {
  return of_type_or_ignored(ctx, ref, key, ref->is_sequence(), "sequence");
}

bool mapping_or_ignored(LoadContext& ctx, const yaml::NodeRef& ref, std::string_view key) {
  return of_type_or_ignored(ctx, ref, key, ref->is_mapping(), "mapping");
}

std::optional<std::vector<double>> read_numbers(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!expect_sequence(ctx, ref, "this value")) return std::nullopt;
  std::vector<double> values;
  values.reserve(ref->items().size());
  for (const yaml::NodeRef& item : ref->items()) {
    auto x = required_double(ctx, ref.child(item));
    if (!x) return std::nullopt;
    values.push_back(*x);
  }
  return values;
}

std::optional<Eigen::Vector3d> read_translation(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!expect_sequence(ctx, ref, "translation")) return std::nullopt;
  if (ref->items().empty()) {
    // body-format-spec §4.2: Choreonoid leaves the value undefined; reject it.
    ctx.report("load-vector-size", ref, "translation is an empty sequence", "write [x, y, z]");
    return std::nullopt;
  }
  if (!is_sequence_of_sequences(ref)) return read_vec3(ctx, ref);
  // A list whose first item is a list is the sum of its items, and Choreonoid reads each item
  // the same way (StdSceneReader::readTranslation is recursive), so an alias to such a sum can
  // be one of the terms: `[ *OFFSET, [0, 0, 0.4] ]`. The YAML depth budget bounds the recursion.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const yaml::NodeRef& item : ref->items()) {
    auto v = read_translation(ctx, ref.child(item));
    if (!v) return std::nullopt;
    sum += *v;
  }
  return sum;
}

std::optional<Eigen::Matrix3d> read_rotation(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!expect_sequence(ctx, ref, "rotation")) return std::nullopt;
  if (ref->items().empty()) {
    ctx.report("load-vector-size", ref, "rotation is an empty sequence", "write [x, y, z, angle]");
    return std::nullopt;
  }
  auto one = [&](const yaml::NodeRef& r) -> std::optional<Eigen::Matrix3d> {
    auto v = read_vector(ctx, r, 4);
    if (!v) return std::nullopt;
    Eigen::Vector3d axis = v->head<3>();
    if (axis.norm() < 1e-6) {
      ctx.report("load-rotation-axis", r, "rotation axis is the zero vector");
      return std::nullopt;
    }
    const yaml::NodeRef angle = r.child(r->items()[3]);
    check_radian_rotation(ctx, angle, (*v)[3]);
    return Eigen::AngleAxisd(ctx.angle((*v)[3], angle), axis.normalized()).toRotationMatrix();
  };
  if (!is_sequence_of_sequences(ref)) return one(ref);
  // body-format-spec §4.3: R = R1 * R2 * ... * Rn in list order.
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (const yaml::NodeRef& item : ref->items()) {
    auto r = one(item);
    if (!r) return std::nullopt;
    R = R * *r;
  }
  return R;
}

std::optional<Eigen::Matrix3d> read_inertia(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!expect_sequence(ctx, ref, "inertia")) return std::nullopt;
  std::size_t n = ref->items().size();
  if (n != 6 && n != 9) {
    ctx.report("load-inertia-size", ref,
               "the number of elements of an inertia value must be six or nine, found " + std::to_string(n));
    return std::nullopt;
  }
  double v[9];
  if (!read_items(ctx, ref, v)) return std::nullopt;
  Eigen::Matrix3d I;
  if (n == 6) {
    I << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
  } else {
    I << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  }
  return I;
}

std::optional<Eigen::Vector3d> read_joint_axis(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (ref && ref->is_scalar()) {
    std::string s(ref->scalar());
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
    double sign = 1;
    if (!s.empty() && s[0] == '-') {
      sign = -1;
      s.erase(0, 1);
    }
    if (s == "X") return Eigen::Vector3d(sign, 0, 0);
    if (s == "Y") return Eigen::Vector3d(0, sign, 0);
    if (s == "Z") return Eigen::Vector3d(0, 0, sign);
    ctx.report("load-axis", ref, "illegal axis value \"" + std::string(ref->scalar()) + "\"",
               "use X, Y, Z, -X, -Y, -Z or [x, y, z]");
    return std::nullopt;
  }
  return read_vec3(ctx, ref);
}

namespace {

// One element of a limit, read as Choreonoid's readLimitValue reads it (StdBodyLoader.cpp): the
// whole scalar as a number (strtod, trailing blanks allowed) or else the word `unlimited`. Any
// other text is refused there ("Unknown symbol is used as a jointRange value"), so unlike the
// other numbers of a file, `0.t` is an error here and not a lenient 0. strtod reads `inf` (and
// an overflowing `1e999`) as infinity: Choreonoid keeps it, an open side, which the model
// holds as kUnlimited with the sign of the value.
std::optional<double> limit_value(LoadContext& ctx, const yaml::NodeRef& ref, bool convert_angle, bool upper) {
  if (!ref || !ref->is_scalar()) {
    ctx.report("load-range", ref, "invalid type value is used as a joint range value");
    return std::nullopt;
  }
  const std::string_view text = ref->scalar();
  if (text == "unlimited") return upper ? kUnlimited : -kUnlimited;
  const std::optional<double> value = parse_double_exact(text);
  if (!value) {
    if (is_yaml_special_float(text)) {
      ctx.report("load-range", ref,
                 "\"" + std::string(text) +
                     "\" is YAML's spelling of infinity or NaN, which Choreonoid's number reader does not know: "
                     "it refuses the file (unknown symbol used as a range value)",
                 "write unlimited");
    } else {
      ctx.report("load-range", ref,
                 "unknown symbol \"" + std::string(text) +
                     "\" is used as a range value; Choreonoid reads a limit whole and refuses the file",
                 "use a number or unlimited");
    }
    return std::nullopt;
  }
  if (std::isnan(*value)) {
    ctx.report("load-number", ref,
               "the value \"" + std::string(text) + "\" is not a number (NaN); a limit must be a number or unlimited",
               "write unlimited");
    return std::nullopt;
  }
  if (std::isinf(*value)) {
    const bool open = (*value > 0) == upper;  // +inf as an upper limit, -inf as a lower one
    std::vector<FixIt> fixes;
    if (open) {
      if (auto fix = edit_value(*ref, "unlimited", FixSafety::kSafe)) fixes.push_back(std::move(*fix));
    }
    ctx.report("load-infinite-limit", ref,
               "\"" + std::string(text) + "\" reads as " + (*value > 0 ? "+" : "-") + "infinity: " +
                   (open ? "an open limit, as `unlimited`"
                         : std::string("an ") + (upper ? "upper" : "lower") +
                               " limit beyond the other side, so the range is empty"),
               open ? "write unlimited, the spelling every reader of the file understands" : "", std::move(fixes));
    return *value > 0 ? kUnlimited : -kUnlimited;
  }
  return convert_angle ? ctx.angle(*value, ref) : *value;
}

}  // namespace

std::optional<std::pair<double, double>> read_range(LoadContext& ctx, const yaml::NodeRef& ref, bool convert_angle) {
  if (!ref) return std::nullopt;
  if (ref->is_scalar()) {
    auto v = limit_value(ctx, ref, convert_angle, true);
    if (!v) return std::nullopt;
    return std::make_pair(-*v, *v);
  }
  if (ref->is_mapping()) {
    ctx.report("load-range", ref, "invalid joint range value (a mapping)");
    return std::nullopt;
  }
  if (ref->items().size() != 2) {
    ctx.report("load-range", ref, "a joint range must have two elements, found " + std::to_string(ref->items().size()));
    return std::nullopt;
  }
  auto lower = limit_value(ctx, ref->items()[0], convert_angle, false);
  auto upper = limit_value(ctx, ref->items()[1], convert_angle, true);
  if (!lower || !upper) return std::nullopt;
  return std::make_pair(*lower, *upper);
}

std::optional<std::pair<double, double>> read_symmetric_limit(LoadContext& ctx, const yaml::NodeRef& ref,
                                                              bool convert_angle) {
  if (!ref) return std::nullopt;
  if (!ref->is_scalar()) {
    ctx.report("load-range", ref, "this limit must be a scalar");
    return std::nullopt;
  }
  auto v = limit_value(ctx, ref, convert_angle, true);
  if (!v) return std::nullopt;
  return std::make_pair(-*v, *v);
}

std::optional<std::pair<double, double>> read_velocity_range(LoadContext& ctx, const yaml::NodeRef& ref,
                                                             bool convert_angle) {
  if (!ref) return std::nullopt;
  if (!ref->is_sequence() || ref->items().size() != 2) {
    ctx.report("load-range", ref, "the joint velocity range must have two elements");
    return std::nullopt;
  }
  auto lower = limit_value(ctx, ref->items()[0], convert_angle, false);
  auto upper = limit_value(ctx, ref->items()[1], convert_angle, true);
  if (!lower || !upper) return std::nullopt;
  return std::make_pair(*lower, *upper);
}

}  // namespace bodyfmt::detail
