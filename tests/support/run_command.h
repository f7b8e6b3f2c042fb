#pragma once
// Runs a command line as a user types it, for tests that drive the tools from the outside.
#include <string>

namespace bodyfmt::test {

struct CommandResult {
  int status = -1;     ///< the exit code; -1 when the command did not exit normally
  std::string output;  ///< standard output, then standard error when `merge_stderr`
};

/// Runs `command` with bash (so <(...), arrays and `&` work) in `directory`.
CommandResult run_command(const std::string& command, const std::string& directory = ".", bool merge_stderr = true);

}  // namespace bodyfmt::test
