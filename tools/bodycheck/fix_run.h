#pragma once
// `bodycheck --fix`: applies the fix-its of each named model's findings to its files, proves by
// re-loading that the model is unchanged, and writes the files atomically (or prints a diff).

#include "front.h"

#include <string>
#include <vector>

namespace bodyfmt::tools {

struct FixSettings {
  bool dry_run = false;   ///< print a unified diff instead of writing
  bool upgrade = false;   ///< also apply the format 1.0 -> 2.0 fix-its
  bool includes = false;  ///< also edit SubBody and YAML resource files not named on the command line
  /// `--fix=geometry`: only the centres of mass and inertias computed from the shapes at the written
  /// masses (link-level keys and RigidBody elements), for the links that inertia-implausible,
  /// -triangle, -not-positive-definite or -com-outside flag
  bool geometry = false;
  /// `--all-links`: with `geometry`, every link's mass data, RigidBody elements included
  bool all_links = false;
};

struct FixSummary {
  int files_changed = 0;
  int edits = 0;
  bool failed = false;  ///< a file could not be fixed (I/O, YAML errors, model changed): exit 2
  std::string diff;     ///< dry run: the unified diff of every file that would change
};

/// Fixes `files` (paths as the user gave them) one model at a time, in order.
FixSummary run_fixes(Front& front, const std::vector<std::string>& files, const FixSettings& settings);

}  // namespace bodyfmt::tools
