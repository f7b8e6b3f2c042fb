#pragma once
/// bodyls's core: one language server session (LSP 3.17) over message bodies, without any I/O
/// of its own, so that the process (run_server) and the fuzz target drive the same code.
///
/// Checks run after a debounce on a worker thread (threaded) or when run_pending_checks() is
/// called (synchronous: the fuzz target and the unit tests, with no thread at all).

#include "front.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::lsp {

struct ServerOptions {
  /// From an edit made while a check is pending or running to its check; an edit made while
  /// the findings are up to date is checked at once (initializationOptions.debounceMs).
  int debounce_ms = 50;
  bool threaded = true;
  int poll_ms = 1000;         ///< the server's own watch of dependency files, when the client has none
  std::string bodyview_path;  ///< bodyview for bodyls.openViewer (empty: beside this program)
  /// The most findings of one check published (initializationOptions.maxDiagnostics): errors
  /// first, then a finding that says how many more bodycheck lists.
  std::size_t max_published = 1000;
};

class Server {
 public:
  /// `send` writes one outgoing message body (it is called from the worker thread too, never
  /// concurrently).
  using Send = std::function<void(const std::string& body)>;
  Server(tools::Front& front, ServerOptions options, Send send);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  /// Handles the messages read in one go: a `$/cancelRequest` among them cancels a request
  /// before it of the same batch, and no check starts until the last is handled (a client's
  /// batch of edits is one burst).
  void handle_batch(const std::vector<std::string>& bodies);
  void handle(const std::string& body);
  /// A frame that is not the protocol's: the parse error, with a null id.
  void bad_frame(const std::string& why);

  /// The client's process id from `initialize`, when it was alive then (the server ends when
  /// it dies, as the protocol asks).
  std::optional<int> client_process() const;
  /// Ends the viewers the session started; the process is about to end.
  void end_viewers();

  /// Synchronous mode: checks every document with an edit not yet checked, now.
  void run_pending_checks();

  bool exited() const;
  /// 0 after `shutdown` then `exit`, 1 for an `exit` (or the end of input) without `shutdown`.
  int exit_code() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// The process: bodycheck's loading and policy options on the command line, messages on
/// standard input and output. Returns the exit code.
int run_server(int argc, char** argv);

}  // namespace bodyfmt::lsp
