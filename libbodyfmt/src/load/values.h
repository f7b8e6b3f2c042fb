#pragma once
// Composite values of the Body format (body-format-spec §4): vectors, translations,
// rotations, inertia, joint axes and ranges. All results are SI and radians.

#include "load/load_context.h"

#include <Eigen/Geometry>

#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace bodyfmt::detail {

/// A flat sequence of exactly `size` numbers (required, lenient conversions).
std::optional<Eigen::VectorXd> read_vector(LoadContext& ctx, const yaml::NodeRef& ref, int size);
std::optional<Eigen::Vector3d> read_vec3(LoadContext& ctx, const yaml::NodeRef& ref);
/// Optional vector keys (shape/device parameters): a scalar or mapping in their place is
/// treated by Choreonoid as absent; we warn and return nullopt.
std::optional<Eigen::Vector3d> read_optional_vec3(LoadContext& ctx, const yaml::NodeRef& ref);
/// Keys Choreonoid reads with findListing / findMapping: a value of another YAML type (a
/// scalar, an empty `key:`) is skipped there without a word. True when `ref` has the expected
/// type; otherwise a load-ignored-value warning at the value, naming `key`, and false.
bool listing_or_ignored(LoadContext& ctx, const yaml::NodeRef& ref, std::string_view key);
bool mapping_or_ignored(LoadContext& ctx, const yaml::NodeRef& ref, std::string_view key);
/// A flat list of numbers of any length, each leniently converted.
std::optional<std::vector<double>> read_numbers(LoadContext& ctx, const yaml::NodeRef& ref);

/// `translation`: a vec3, or a list of vec3 that are summed.
std::optional<Eigen::Vector3d> read_translation(LoadContext& ctx, const yaml::NodeRef& ref);
/// `rotation`: axis-angle [x, y, z, angle] or a list of them, composed R1 * R2 * ... Rn.
/// `angles_are_file_unit` = false for keys that are always radians.
std::optional<Eigen::Matrix3d> read_rotation(LoadContext& ctx, const yaml::NodeRef& ref);
/// `inertia`: 6 (upper triangle) or 9 (row-major) numbers.
std::optional<Eigen::Matrix3d> read_inertia(LoadContext& ctx, const yaml::NodeRef& ref);
/// `joint_axis`: vec3 (not normalised) or X, Y, Z, -X, -Y, -Z (any case).
std::optional<Eigen::Vector3d> read_joint_axis(LoadContext& ctx, const yaml::NodeRef& ref);

/// `joint_range`: scalar v -> [-v, v], `unlimited`, or [lower, upper] with `unlimited`
/// allowed per element. `convert_angle` applies the file's angle unit.
std::optional<std::pair<double, double>> read_range(LoadContext& ctx, const yaml::NodeRef& ref, bool convert_angle);
/// `max_joint_velocity` / `max_joint_effort`: scalar v (or `unlimited`) -> [-v, v].
std::optional<std::pair<double, double>> read_symmetric_limit(LoadContext& ctx, const yaml::NodeRef& ref,
                                                              bool convert_angle);
/// `joint_velocity_range`: exactly two elements.
std::optional<std::pair<double, double>> read_velocity_range(LoadContext& ctx, const yaml::NodeRef& ref,
                                                             bool convert_angle);

}  // namespace bodyfmt::detail
