#pragma once
/// `bodyls.openViewer`: one `bodyview --serve` per model file, started on request and ended
/// with the server. bodyview serves the file as saved and reloads it on each save.

#include <sys/types.h>

#include <map>
#include <mutex>
#include <optional>
#include <string>

namespace bodyfmt::lsp {

class ViewerLauncher {
 public:
  /// `bodyview`: its path (empty: `bodyview` beside this program).
  explicit ViewerLauncher(std::string bodyview);
  ~ViewerLauncher();  ///< ends every viewer it started
  /// Ends every viewer it started, now.
  void end_all();
  ViewerLauncher(const ViewerLauncher&) = delete;
  ViewerLauncher& operator=(const ViewerLauncher&) = delete;

  /// The URL of the viewer of `path` (started now, or still running from before), or nullopt
  /// with `why`.
  std::optional<std::string> url_for(const std::string& path, std::string& why);

 private:
  struct Viewer {
    pid_t pid = -1;
    std::string url;
  };
  std::string bodyview_;
  std::mutex mutex_;
  std::map<std::string, Viewer> viewers_;
};

}  // namespace bodyfmt::lsp
