#pragma once
// bodydiff's four ways to run, each returning the tool's exit code: two files, one file's
// canonical text for git (textconv), git's external diff driver, and each file against a git
// revision or the index.

#include "front.h"

#include <bodyfmt/model_diff.h>

#include <string>
#include <vector>

namespace bodyfmt::tools {

struct DiffRun {
  Front& front;
  ModelDiffOptions options;
  std::string format;  ///< "text" or "json"
};

/// OLD NEW: 0 the same, 1 they differ, 2 a model cannot be loaded.
int diff_two_files(const DiffRun& run, const std::vector<std::string>& args);

/// --textconv FILE: the model's canonical text.
int print_textconv(const DiffRun& run, const std::vector<std::string>& args);

/// --git: git's 7 (or 9) external-diff arguments; exits 0 when the models differ, as git expects.
int git_diff_driver(const DiffRun& run, const std::vector<std::string>& args);

/// --git-rev REV (or --staged: the index against HEAD) FILE...
int diff_against_git(const DiffRun& run, const std::vector<std::string>& args, std::string git_rev, bool staged);

}  // namespace bodyfmt::tools
