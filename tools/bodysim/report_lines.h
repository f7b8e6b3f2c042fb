#pragma once
/// bodysim's report as a user reads it in a terminal: every line within 100 columns, a check
/// named in words with its code from dynamics-checker.md in brackets at the end, and numbers
/// printed with as many digits as it takes to tell measured from expected.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/dynamics/checks.h>

#include <string>
#include <vector>

namespace bodyfmt::tools {

constexpr std::size_t kReportColumns = 100;

/// `text` broken at spaces into lines of at most kReportColumns (a word longer than a line
/// stays whole), each after the first indented by `indent` spaces; every line ends with '\n'.
std::string wrap(const std::string& text, std::size_t indent);

/// `value` to 6 significant digits, as the report prints a quantity.
std::string number(double value);

/// `value` and `other` to 6 significant digits, or more (up to 10) while the two would print
/// the same but differ: a comparison that fails for a difference in the 7th digit shows it.
std::pair<std::string, std::string> distinct_numbers(double value, double other);

/// One check: "PASS  name [G3]" then "      measured ...  expected ...  tolerance ...", or
/// "SKIP  name: reason", wrapped.
std::string check_lines(const dynamics::CheckResult& result);

/// The end of a run that simulated nothing: the reason, the first error that stopped it (its
/// location, message and rule) and its hint, which names the option that lets the model run.
std::string nothing_simulated(const std::string& tool, const std::string& why,
                              const std::vector<Diagnostic>& diagnostics);

}  // namespace bodyfmt::tools
