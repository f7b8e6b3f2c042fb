#include "viewer_launcher.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstring>
#include <thread>
#include <vector>

namespace bodyfmt::lsp {

namespace {

std::string beside_this_program(const std::string& name) {
  char self[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return name;
  std::string path(self, static_cast<std::size_t>(n));
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? name : path.substr(0, slash + 1) + name;
}

/// The first line `fd` gives within `seconds`, or nullopt at its end or on time-out.
std::optional<std::string> first_line(int fd, int seconds) {
  std::string line;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return std::nullopt;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return std::nullopt;
    char c;
    const ssize_t n = ::read(fd, &c, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return std::nullopt;
    if (c == '\n') return line;
    if (line.size() < 4096) line += c;
  }
}

}  // namespace

ViewerLauncher::ViewerLauncher(std::string bodyview)
    : bodyview_(bodyview.empty() ? beside_this_program("bodyview") : std::move(bodyview)) {}

ViewerLauncher::~ViewerLauncher() { end_all(); }

void ViewerLauncher::end_all() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [path, viewer] : viewers_) {
    ::kill(viewer.pid, SIGTERM);
    ::waitpid(viewer.pid, nullptr, 0);
  }
  viewers_.clear();
}

std::optional<std::string> ViewerLauncher::url_for(const std::string& path, std::string& why) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = viewers_.find(path); it != viewers_.end()) {
    if (::waitpid(it->second.pid, nullptr, WNOHANG) == 0) return it->second.url;
    viewers_.erase(it);  // it has ended: start another
  }
  if (::access(bodyview_.c_str(), X_OK) != 0) {
    why = "cannot run " + bodyview_ + " (bodyview is looked for beside bodyls)";
    return std::nullopt;
  }
  int out[2];
  if (::pipe2(out, O_CLOEXEC) != 0) {
    why = std::string("cannot make a pipe: ") + std::strerror(errno);
    return std::nullopt;
  }
  // Everything the child needs is made before fork(): after it, only exec-safe calls.
  std::vector<std::string> args = {bodyview_, "--serve", path};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int null_in = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    if (null_in >= 0) ::dup2(null_in, STDIN_FILENO);  // the editor's messages are not for it
    ::signal(SIGPIPE, SIG_DFL);                       // bodyls ignores it (run_server); an ignored signal survives exec
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(out[1]);
  if (null_in >= 0) ::close(null_in);
  if (pid < 0) {
    ::close(out[0]);
    why = std::string("cannot start bodyview: ") + std::strerror(errno);
    return std::nullopt;
  }
  const std::optional<std::string> url = first_line(out[0], 60);
  if (!url || url->rfind("http://", 0) != 0) {
    ::close(out[0]);
    ::kill(pid, SIGTERM);
    ::waitpid(pid, nullptr, 0);
    why = "bodyview --serve " + path + " did not serve the page (see its errors in the server's log)";
    return std::nullopt;
  }
  // Whatever else it prints is read and dropped, so that it never blocks on a full pipe.
  std::thread([fd = out[0]] {
    char buffer[4096];
    while (::read(fd, buffer, sizeof buffer) > 0) {
    }
    ::close(fd);
  }).detach();
  viewers_[path] = Viewer{pid, *url};
  return url;
}

}  // namespace bodyfmt::lsp
