#pragma once
// Shape geometry nodes (body-format-spec §9).

#include <bodyfmt/model.h>

#include "load/load_context.h"

#include <optional>
#include <string>
#include <string_view>

namespace bodyfmt::detail {

/// Reads a `geometry` mapping. `division_number` is set when the node gives one.
std::optional<Geometry> read_geometry(LoadContext& ctx, const yaml::NodeRef& geometry, int& division_number);

/// The division number Choreonoid uses for a written `n` (a shape's division_number, a
/// wrapper's geometry.divisionNumber): below 4 the default 20, above kMaxDivisionNumber
/// clamped, with geometry-division-clamped at `at` naming `key` as written.
int division_number_from(LoadContext& ctx, const yaml::NodeRef& at, long n, std::string_view key);

}  // namespace bodyfmt::detail
