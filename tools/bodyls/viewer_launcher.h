#pragma once
/// `bodyls.openViewer`: one `bodyview --serve` per model file, started on request and ended
/// with the server. bodyview serves the file as saved and reloads it on each save.
///
/// A viewer starts without holding anything up: its first line (the URL) is awaited on a thread
/// of its own, and the request is answered from there. Viewers are kept by the file's canonical
/// path, so every spelling of one file's URI shares one viewer, and at most kMostViewers run at
/// once: a request beyond that ends the least recently requested one. Each viewer watches a pipe
/// whose write end only this process holds (`bodyview --lifeline`): however bodyls ends, even by
/// SIGKILL, its viewers end with it.

#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace bodyfmt::lsp {

class ViewerLauncher {
 public:
  /// Viewers that run at once: each is a process of 15 MB and more, a page in a browser's tab.
  static constexpr std::size_t kMostViewers = 8;

  /// `url`, or nullopt with `why`.
  using Done = std::function<void(const std::optional<std::string>& url, const std::string& why)>;

  /// `bodyview`: its path (empty: `bodyview` beside this program).
  explicit ViewerLauncher(std::string bodyview);
  ~ViewerLauncher();  ///< ends every viewer at once, answering no request still waiting
  ViewerLauncher(const ViewerLauncher&) = delete;
  ViewerLauncher& operator=(const ViewerLauncher&) = delete;

  /// Calls `done` with the URL of the viewer of `path` once it serves: at once when it runs
  /// already, else from the thread that waits for it. Sets `ended` to the file whose viewer was
  /// ended to keep to kMostViewers (else leaves it).
  void open(const std::string& path, Done done, std::string& ended);

  /// Ends every viewer, starting or running, and answers the requests still waiting with `why`
  /// (none when it is empty); nothing starts after it. Waits for nothing.
  void end_all(const std::string& why);

 private:
  struct Viewer {
    pid_t pid = -1;
    int out = -1;                 ///< its standard output
    std::string path;             ///< the file, as bodyview was given it
    std::string url;              ///< empty while it starts
    bool ended = false;           ///< it failed, was ended, or closed its output
    std::uint64_t requested = 0;  ///< when it was last asked for (request_count_)
    std::vector<Done> waiting;    ///< requests to answer once it serves
    std::thread watcher;
    std::atomic<bool> finished{false};  ///< the watcher has returned: joining it does not wait
  };
  void watch(Viewer& viewer);
  std::optional<std::string> start(const std::string& path, Viewer& viewer);
  void retire_ended();
  bool make_room(std::string& ended);

  std::string bodyview_;
  int lifeline_[2] = {-1, -1};  ///< read end: every viewer's; write end: ours alone
  int wake_[2] = {-1, -1};      ///< written once by end_all: every watcher stops waiting
  std::mutex mutex_;
  bool stopping_ = false;
  std::uint64_t request_count_ = 0;
  std::map<std::string, std::unique_ptr<Viewer>> viewers_;  ///< by canonical path
  std::vector<std::unique_ptr<Viewer>> retired_;            ///< ended, their watchers yet to be joined
};

}  // namespace bodyfmt::lsp
