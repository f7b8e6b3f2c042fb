#pragma once
// Shape geometry nodes (body-format-spec §9).

#include <bodyfmt/model.h>

#include "load/load_context.h"
#include "load/mapping_reader.h"

#include <optional>
#include <string>
#include <string_view>

namespace bodyfmt::detail {

/// The mesh node a Resource names. Choreonoid looks for `fragment` before `node`
/// (StdSceneReader::readResource): with both written, `fragment` wins and `node` is reported.
yaml::NodeRef take_resource_node(LoadContext& ctx, MappingReader& r);

/// Reads a `geometry` mapping. `division_number` is set when the node gives one.
std::optional<Geometry> read_geometry(LoadContext& ctx, const yaml::NodeRef& geometry, int& division_number);

/// The division number Choreonoid uses for a written `n` (a shape's division_number, a
/// wrapper's geometry.divisionNumber): below 4 the default 20, above kMaxDivisionNumber
/// clamped, with geometry-division-clamped at `at` naming `key` as written.
int division_number_from(LoadContext& ctx, const yaml::NodeRef& at, long n, std::string_view key);

}  // namespace bodyfmt::detail
