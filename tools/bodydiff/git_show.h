#pragma once
// Reading a file's text at a git revision (`bodydiff --git-rev`), through the git program.

#include <cstdint>
#include <optional>
#include <string>

namespace bodyfmt::tools {

/// A file's text at a revision, or why there is none.
struct GitFile {
  std::optional<std::string> text;  ///< the text; nullopt when the file is not there
  bool absent = false;              ///< git said the path is not in that revision (or the index)
  std::string why;                  ///< git's message when `text` is nullopt
};

/// The text of `path` (relative to the working folder) at `revision` ("": git's index), read
/// with `git cat-file blob REVISION:./PATH`. Only git's own "does not exist in 'REV'" and
/// "exists on disk, but not in 'REV'" (or "... the index") make the file absent; any other
/// failure (a path outside the repository, a folder, no repository) is an error in `why`, and
/// so is a blob larger than `max_bytes` (the loader's file-size limit): reading stops there.
GitFile git_show(const std::string& revision, const std::string& path, std::uintmax_t max_bytes);

/// True when `revision` names a commit in the repository of the working folder.
bool git_commit_exists(const std::string& revision, std::string& why);

}  // namespace bodyfmt::tools
