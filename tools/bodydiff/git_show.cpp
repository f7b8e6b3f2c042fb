#include "git_show.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

extern char** environ;

namespace bodyfmt::tools {
namespace {

// Runs git with `args` (no shell: a revision or path is never interpreted), returns its exit
// status and collects stdout and stderr.
int run_git(const std::vector<std::string>& args, std::string& out, std::string& err) {
  int out_pipe[2], err_pipe[2];
  if (pipe(out_pipe) != 0) return -1;
  if (pipe(err_pipe) != 0) {
    close(out_pipe[0]), close(out_pipe[1]);
    return -1;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
  posix_spawn_file_actions_addclose(&actions, out_pipe[0]);
  posix_spawn_file_actions_addclose(&actions, err_pipe[0]);
  std::vector<char*> argv;
  std::string git = "git";
  argv.push_back(git.data());
  std::vector<std::string> copies = args;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "git", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out_pipe[1]);
  close(err_pipe[1]);
  if (spawned != 0) {
    close(out_pipe[0]), close(err_pipe[0]);
    err = std::string("cannot run git: ") + std::strerror(spawned);
    return -1;
  }
  // git's stderr is short; reading stdout to the end first cannot block on a full stderr pipe
  // for the messages git writes.
  char buffer[65536];
  for (ssize_t n; (n = read(out_pipe[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    out.append(buffer, static_cast<std::size_t>(n));
  }
  for (ssize_t n; (n = read(err_pipe[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    err.append(buffer, static_cast<std::size_t>(n));
  }
  close(out_pipe[0]);
  close(err_pipe[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

GitFile git_show(const std::string& revision, const std::string& path) {
  GitFile file;
  std::string out, err;
  if (run_git({"cat-file", "blob", revision + ":./" + path}, out, err) == 0) {
    file.text = std::move(out);
    return file;
  }
  file.why = err.empty() ? "git cat-file failed on " + revision + ":./" + path : first_line(err);
  // git's wording (builtin object-name.c) for a path that is simply not in the tree or index.
  const std::string& why = file.why;
  auto has = [&](const char* words) { return why.find(words) != std::string::npos; };
  file.absent =
      why.rfind("fatal: path '", 0) == 0 && (has("' does not exist in '") || has("' exists on disk, but not in ") ||
                                             has("' does not exist (neither on disk nor in the index)"));
  return file;
}

bool git_commit_exists(const std::string& revision, std::string& why) {
  std::string out, err;
  if (run_git({"rev-parse", "--verify", "--quiet", revision + "^{commit}"}, out, err) == 0) return true;
  why = err.empty() ? "not a commit: " + revision : first_line(err);
  return false;
}

}  // namespace bodyfmt::tools
