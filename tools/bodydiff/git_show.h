#pragma once
// Reading a file's text at a git revision (`bodydiff --git-rev`), through the git program.

#include <optional>
#include <string>

namespace bodyfmt::tools {

/// The text of `path` (relative to the working folder) at `revision`, read with
/// `git show REVISION:./PATH`; nullopt when git fails (no such revision, or no such file there),
/// with git's message in `why`.
std::optional<std::string> git_show(const std::string& revision, const std::string& path, std::string& why);

/// True when `revision` names a commit in the repository of the working folder.
bool git_commit_exists(const std::string& revision, std::string& why);

}  // namespace bodyfmt::tools
