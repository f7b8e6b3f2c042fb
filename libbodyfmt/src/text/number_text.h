#pragma once
// Numbers read from text the way Choreonoid's strtod reads them, below the YAML layer and the
// loader (which add the diagnostics: load/scalar.h). No YAML, no model.

#include <optional>
#include <string_view>

namespace bodyfmt::detail {

/// Parses a whole scalar as a double, nothing else (no diagnostics). `text.data()` must be
/// NUL-terminated, as a yaml::Node's scalar is.
std::optional<double> parse_double_exact(std::string_view text);

/// The fast path of parse_double_exact and of the loader's required_double: `text` when it is a whole, finite decimal
/// number such as `-0.25` or `1e-3` (the value strtod gives), nullopt for anything else, which strtod then reads.
std::optional<double> parse_plain_decimal(std::string_view text);

/// YAML 1.1's own spellings of NaN and infinity (`.nan`, `.inf`, `-.Inf`, ...): floats to a YAML
/// reader, text that Choreonoid's strtod cannot read.
bool is_yaml_special_float(std::string_view text);

/// True when only blanks and line breaks are left before the NUL at `p`.
bool only_trailing_space(const char* p);

}  // namespace bodyfmt::detail
