#pragma once
/// Numbers in messages, as a person reads them: `13.5`, not the `13.500000000000002` that the
/// arithmetic left. Text meant to be read back (fix-its, written files, the JSON and YAML reports)
/// keeps the shortest round-trip form instead.

#include <bodyfmt/export.h>

#include <string>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// At most 6 significant digits, without trailing zeros (`{:.6g}`): 0.1 + 0.2 is "0.3", 1/3 is
/// "0.333333", 1e-7 is "1e-07". Zero is "0" whatever its sign; infinities and NaN are "inf",
/// "-inf" and "nan".
std::string readable_number(double value);

}  // namespace bodyfmt
#pragma GCC visibility pop
