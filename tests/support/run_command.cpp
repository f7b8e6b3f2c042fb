#include "run_command.h"

#include <doctest/doctest.h>

#include <sys/wait.h>

#include <cstdio>

namespace bodyfmt::test {

namespace {

std::string single_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

CommandResult run_command(const std::string& command, const std::string& directory, bool merge_stderr) {
  const std::string script =
      "cd " + single_quoted(directory) + " && { " + command + "\n}" + (merge_stderr ? " 2>&1" : "");
  CommandResult result;
  FILE* pipe = popen(("bash -c " + single_quoted(script)).c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace bodyfmt::test
