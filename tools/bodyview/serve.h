#pragma once
// bodyview --serve: the page on a loopback port, rebuilt when the model, a file it includes or
// a mesh changes; a load that fails keeps the last good page and shows its diagnostics. Clients
// are served concurrently from one poll() loop with a deadline each, answered only under the
// loopback host names of the URL (GET and HEAD), and a signal stops it within a tick.

#include "front.h"

#include <filesystem>
#include <string>

namespace bodyfmt::bodyview {

/// Serves until interrupted (SIGINT/SIGTERM: exit 0). `port` 0 picks a free one; the URL is
/// printed to standard output. Returns 2 when the socket cannot be opened or the first load is
/// fatal. A page's findings are printed as one summary line unless `verbose`.
/// Watches file descriptor `fd` on a thread of its own, and ends the process (exit 0) as soon as
/// it reads its end: `--lifeline`, the read end of a pipe whose writer started this process.
/// False when `fd` is not open.
bool exit_with_lifeline(int fd);

int serve(tools::Front& front, const tools::Front::FilePolicy& policy, const std::string& path,
          const std::filesystem::path& assets, int port, bool verbose);

}  // namespace bodyfmt::bodyview
