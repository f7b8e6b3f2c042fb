#pragma once
// Scalar conversions with Choreonoid's two strictness levels (body-format-spec §1.2):
// "required" values are read leniently like strtod (we accept and warn), "optional" values
// must parse whole or Choreonoid silently falls back to the default (we do too, and warn).

#include "load/load_context.h"
#include "text/number_text.h"

#include <optional>
#include <string>
#include <string_view>

namespace bodyfmt::detail {

std::optional<double> required_double(LoadContext& ctx, const yaml::NodeRef& ref);
std::optional<long> required_int(LoadContext& ctx, const yaml::NodeRef& ref);
std::optional<bool> required_bool(LoadContext& ctx, const yaml::NodeRef& ref);
std::optional<std::string> required_string(LoadContext& ctx, const yaml::NodeRef& ref);

/// Whole-scalar reads. On failure they warn that Choreonoid ignores the value and return
/// nullopt, so the caller keeps its default.
std::optional<double> optional_double(LoadContext& ctx, const yaml::NodeRef& ref);
std::optional<long> optional_int(LoadContext& ctx, const yaml::NodeRef& ref);
std::optional<bool> optional_bool(LoadContext& ctx, const yaml::NodeRef& ref);

}  // namespace bodyfmt::detail
