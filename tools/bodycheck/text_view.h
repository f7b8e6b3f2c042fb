#pragma once
// bodycheck's text report for a person at a terminal or reading a failed hook: errors first,
// the warnings and notes one rule repeats in a file folded into one block with their lines,
// and a closing summary that says what `--fix` would fix. JSON and SARIF keep every finding;
// this view only decides what is printed, in which order.

#include <bodyfmt/report.h>

#include <ostream>
#include <string>
#include <vector>

namespace bodyfmt::tools {

struct TextView {
  TextOptions text;
  Severity min_severity = Severity::kNote;  ///< --min-severity: findings below are counted, not printed
  bool summary = true;                      ///< the closing lines (not with -q)
  std::vector<std::string> paths;           ///< the paths checked, for the `--fix` command it suggests
};

/// Writes `report` as text: fatal errors and errors, then warnings, then notes, each in file and
/// line order; a warning or note whose rule has kFoldAt or more findings in the same file is
/// printed once in full, followed by one line with the other locations.
void write_text_view(std::ostream& out, const Report& report, SourceLines& sources, const TextView& view);

/// Findings of one rule in one file from which they are folded into one block.
constexpr int kFoldAt = 3;

}  // namespace bodyfmt::tools
