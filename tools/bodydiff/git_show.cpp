#include "git_show.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <vector>

extern char** environ;

namespace bodyfmt::tools {
namespace {

// What of git's standard error is kept: its messages are a line or two.
constexpr std::size_t kMaxErrorBytes = 64 * 1024;

// Runs git with `args` (no shell: a revision or path is never interpreted), returns its exit
// status and collects stdout (up to `max_out` bytes and one more, which tells that there was
// more: git is then stopped) and stderr.
int run_git(const std::vector<std::string>& args, std::string& out, std::string& err,
            std::uintmax_t max_out = 1 << 20) {
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
  bool stopped = false;
  for (ssize_t n; (n = read(out_pipe[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    out.append(buffer, static_cast<std::size_t>(n));
    if (out.size() > max_out) {
      out.resize(static_cast<std::size_t>(max_out) + 1);
      kill(pid, SIGTERM);
      stopped = true;
      break;
    }
  }
  for (ssize_t n; (n = read(err_pipe[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    if (err.size() < kMaxErrorBytes) err.append(buffer, static_cast<std::size_t>(n));
  }
  close(out_pipe[0]);
  close(err_pipe[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (stopped) return -2;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

GitFile git_show(const std::string& revision, const std::string& path, std::uintmax_t max_bytes) {
  GitFile file;
  std::string out, err;
  const int status = run_git({"cat-file", "blob", revision + ":./" + path}, out, err, max_bytes);
  if (status == 0) {
    file.text = std::move(out);
    return file;
  }
  if (status == -2) {
    // the words of the bounded file reader (bodyfmt/read_file.h), for a blob
    file.why = fmt::format("{} {} is larger than the limit of {} bytes (--max-file-size)", path,
                           revision.empty() ? "in the index" : "at " + revision, max_bytes);
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
