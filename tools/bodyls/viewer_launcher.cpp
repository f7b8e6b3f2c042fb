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
#include <filesystem>

namespace bodyfmt::lsp {

namespace {

using Clock = std::chrono::steady_clock;
/// How long a viewer may take to print its URL: a large model's first page takes seconds.
constexpr auto kStartTime = std::chrono::seconds(60);
/// How long an ended viewer may take to exit on SIGTERM before SIGKILL.
constexpr auto kExitTime = std::chrono::seconds(2);

std::string beside_this_program(const std::string& name) {
  char self[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return name;
  std::string path(self, static_cast<std::size_t>(n));
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? name : path.substr(0, slash + 1) + name;
}

/// Waits until `fd` can be read or `wake` was written, up to `until`: true for `fd`.
bool wait_readable(int fd, int wake, Clock::time_point until) {
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p[2] = {{fd, POLLIN, 0}, {wake, POLLIN, 0}};
    const int ready = ::poll(p, 2, static_cast<int>(std::min<long long>(left, INT_MAX)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0 || p[1].revents) return false;
    return true;
  }
}

/// The first line `fd` gives by `until`, or nullopt at its end, on time-out, or on a wake.
std::optional<std::string> first_line(int fd, int wake, Clock::time_point until) {
  std::string line;
  for (;;) {
    if (!wait_readable(fd, wake, until)) return std::nullopt;
    char c;
    const ssize_t n = ::read(fd, &c, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return std::nullopt;
    if (c == '\n') return line;
    if (line.size() < 4096) line += c;
  }
}

/// Ends `pid`, a child not yet waited for (so its id is still ours): SIGTERM, then SIGKILL when
/// it is still there after kExitTime.
void end_child(pid_t pid) {
  ::kill(pid, SIGTERM);
  const Clock::time_point until = Clock::now() + kExitTime;
  while (Clock::now() < until) {
    const pid_t done = ::waitpid(pid, nullptr, WNOHANG);
    if (done == pid || (done < 0 && errno != EINTR)) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGKILL);
  while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
  }
}

}  // namespace

ViewerLauncher::ViewerLauncher(std::string bodyview)
    : bodyview_(bodyview.empty() ? beside_this_program("bodyview") : std::move(bodyview)) {
  // Close-on-exec: no child of ours, a viewer or any other, holds the write end, which is what
  // lets the viewers see its end. The read end is handed to each viewer on purpose (start).
  if (::pipe2(lifeline_, O_CLOEXEC) != 0) lifeline_[0] = lifeline_[1] = -1;
  if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) wake_[0] = wake_[1] = -1;
}

ViewerLauncher::~ViewerLauncher() {
  end_all("");
  for (auto& [path, viewer] : viewers_) viewer->watcher.join();
  for (auto& viewer : retired_) viewer->watcher.join();
  for (int fd : {lifeline_[0], wake_[0], wake_[1]})
    if (fd >= 0) ::close(fd);
}

void ViewerLauncher::end_all(const std::string& why) {
  std::vector<Done> waiting;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!stopping_) {
      stopping_ = true;
      // Every viewer exits on its lifeline's end, at once, even one still in its first load (a
      // FIFO blocks it there); SIGTERM below is for one that ignores the lifeline.
      if (lifeline_[1] >= 0) ::close(lifeline_[1]);
      lifeline_[1] = -1;
      for (auto& [path, viewer] : viewers_) {
        for (Done& done : viewer->waiting) waiting.push_back(std::move(done));
        viewer->waiting.clear();
        if (!viewer->ended) ::kill(viewer->pid, SIGTERM);  // its watcher waits for it to go
      }
      // Never read: it stays readable, so every watcher, now or later, stops waiting.
      if (wake_[1] >= 0) (void)!::write(wake_[1], "x", 1);
    }
  }
  if (!why.empty())
    for (Done& done : waiting) done(std::nullopt, why);
}

void ViewerLauncher::open(const std::string& path, Done done, std::string& ended) {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto fail = [&](const std::string& why) {
    lock.unlock();
    done(std::nullopt, why);
  };
  if (stopping_) return fail("bodyls is shutting down");
  if (wake_[0] < 0) return fail("cannot make a pipe");
  // One viewer per file, however its URI spells it: ./, //, .., a symbolic link, %-escapes.
  std::error_code ec;
  const std::string key = std::filesystem::canonical(path, ec).string();
  if (ec) return fail("cannot open " + path + ": " + ec.message());
  retire_ended();
  if (auto it = viewers_.find(key); it != viewers_.end()) {
    Viewer& viewer = *it->second;
    viewer.requested = ++request_count_;
    if (viewer.url.empty()) {
      viewer.waiting.push_back(std::move(done));  // answered with the first request's
      return;
    }
    const std::string url = viewer.url;
    lock.unlock();
    return done(url, "");
  }
  if (!make_room(ended))
    return fail("at most " + std::to_string(kMostViewers) + " viewers run at once, and " +
                std::to_string(kMostViewers) + " are starting; ask again once one serves");
  auto viewer = std::make_unique<Viewer>();
  if (std::optional<std::string> why = start(key, *viewer)) return fail(*why);
  viewer->requested = ++request_count_;
  viewer->waiting.push_back(std::move(done));
  Viewer& started = *viewer;
  viewers_[key] = std::move(viewer);
  started.watcher = std::thread([this, &started] { watch(started); });
}

void ViewerLauncher::retire_ended() {
  for (auto it = viewers_.begin(); it != viewers_.end();) {
    if (it->second->ended) {
      retired_.push_back(std::move(it->second));
      it = viewers_.erase(it);
    } else {
      ++it;
    }
  }
  // Their watchers have returned: joining them does not wait (and keeps threads from piling up).
  for (auto it = retired_.begin(); it != retired_.end();) {
    if ((*it)->finished) {
      (*it)->watcher.join();
      it = retired_.erase(it);
    } else {
      ++it;
    }
  }
}

bool ViewerLauncher::make_room(std::string& ended) {
  if (viewers_.size() < kMostViewers) return true;
  // The least recently requested viewer that serves goes: its page is the one least likely to
  // be looked at, and a new request for it starts it again. Starting ones are left to start.
  auto oldest = viewers_.end();
  for (auto it = viewers_.begin(); it != viewers_.end(); ++it)
    if (!it->second->url.empty() && (oldest == viewers_.end() || it->second->requested < oldest->second->requested))
      oldest = it;
  if (oldest == viewers_.end()) return false;
  Viewer& viewer = *oldest->second;
  ended = viewer.path;
  viewer.ended = true;
  ::kill(viewer.pid, SIGTERM);  // its watcher sees its output end and waits for it
  retired_.push_back(std::move(oldest->second));
  viewers_.erase(oldest);
  return true;
}

std::optional<std::string> ViewerLauncher::start(const std::string& path, Viewer& viewer) {
  if (::access(bodyview_.c_str(), X_OK) != 0)
    return "cannot run " + bodyview_ + " (bodyview is looked for beside bodyls, or named by --bodyview)";
  int out[2];
  if (::pipe2(out, O_CLOEXEC) != 0) return std::string("cannot make a pipe: ") + std::strerror(errno);
  // Everything the child needs is made before fork(): after it, only exec-safe calls.
  std::vector<std::string> args = {bodyview_, "--serve", path};
  if (lifeline_[0] >= 0) args.insert(args.end(), {"--lifeline", std::to_string(lifeline_[0])});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int null_in = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const int lifeline = lifeline_[0];
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    if (null_in >= 0) ::dup2(null_in, STDIN_FILENO);   // the editor's messages are not for it
    if (lifeline >= 0) ::fcntl(lifeline, F_SETFD, 0);  // the one descriptor it keeps across exec
    ::signal(SIGPIPE, SIG_DFL);  // bodyls ignores it (run_server); an ignored signal survives exec
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(out[1]);
  if (null_in >= 0) ::close(null_in);
  if (pid < 0) {
    ::close(out[0]);
    return std::string("cannot start bodyview: ") + std::strerror(errno);
  }
  viewer.pid = pid;
  viewer.out = out[0];
  viewer.path = path;
  return std::nullopt;
}

void ViewerLauncher::watch(Viewer& viewer) {
  const std::optional<std::string> line = first_line(viewer.out, wake_[0], Clock::now() + kStartTime);
  const bool serves = line && line->rfind("http://", 0) == 0;
  std::vector<Done> waiting;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    waiting.swap(viewer.waiting);  // empty after end_all, which answered them
    if (serves)
      viewer.url = *line;
    else
      viewer.ended = true;
  }
  const std::string why = "bodyview --serve " + viewer.path + " did not serve the page within " +
                          std::to_string(kStartTime.count()) + " s (see its errors in the server's log)";
  const std::optional<std::string> url = serves ? line : std::nullopt;
  for (Done& done : waiting) done(url, serves ? "" : why);
  // Whatever else it prints is read and dropped, so that it never blocks on a full pipe; its
  // output's end is its own.
  if (serves) {
    char buffer[4096];
    while (wait_readable(viewer.out, wake_[0], Clock::time_point::max())) {
      const ssize_t n = ::read(viewer.out, buffer, sizeof buffer);
      if (n == 0 || (n < 0 && errno != EINTR)) break;
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    viewer.ended = true;
  }
  end_child(viewer.pid);
  ::close(viewer.out);
  viewer.finished = true;
}

}  // namespace bodyfmt::lsp
