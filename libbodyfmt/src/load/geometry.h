#pragma once
// Shape geometry nodes (body-format-spec §9).

#include <bodyfmt/model.h>

#include "load/load_context.h"

#include <optional>
#include <string>

namespace bodyfmt::detail {

/// Reads a `geometry` mapping. `division_number` is set when the node gives one.
std::optional<Geometry> read_geometry(LoadContext& ctx, const yaml::NodeRef& geometry, int& division_number);

}  // namespace bodyfmt::detail
