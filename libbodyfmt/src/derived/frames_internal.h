#pragma once
// Link frames at zero joint positions in the 3x4 storage of Derived::X_WL, for compute_derived:
// the same values as compute_world_frames and compute_root_relative_frames give, without a
// 128-byte isometry per link alive beside them.

#include <bodyfmt/model.h>

#include <vector>

namespace bodyfmt::detail {

std::vector<Eigen::AffineCompact3d> compact_world_frames(const Model& model);
std::vector<Eigen::AffineCompact3d> compact_root_relative_frames(const Model& model);

}  // namespace bodyfmt::detail
