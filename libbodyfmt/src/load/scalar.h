#pragma once
// Scalar conversions with Choreonoid's two strictness levels (body-format-spec §1.2):
// "required" values are read leniently like strtod (we accept and warn), "optional" values
// must parse whole or Choreonoid silently falls back to the default (we do too, and warn).

#include "load/load_context.h"

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

/// Parses a whole scalar as a double, nothing else (no diagnostics). `text.data()` must be
/// NUL-terminated, as a yaml::Node's scalar is.
std::optional<double> parse_double_exact(std::string_view text);

/// The fast path of both: `text` when it is a whole, finite decimal number such as `-0.25`
/// or `1e-3` (the value strtod gives), nullopt for anything else, which strtod then reads.
std::optional<double> parse_plain_decimal(std::string_view text);

}  // namespace bodyfmt::detail
