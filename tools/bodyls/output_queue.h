#pragma once
/// bodyls's standard output: every outgoing message goes through one queue that a writer thread
/// empties, so that no thread that holds the server's state ever waits for the client to read.
/// A client that stops reading blocks only the writer; the reader still sees the end of input
/// (or the client's death) and ends the session, whatever the writer is waiting for.

#include <cstddef>
#include <memory>
#include <string>

namespace bodyfmt::lsp {

class OutputQueue {
 public:
  explicit OutputQueue(int fd);
  /// Never waits for the writer: one blocked in write() to a client that no longer reads would
  /// never end. It owns what it uses, and the process ends around it.
  ~OutputQueue();
  OutputQueue(const OutputQueue&) = delete;
  OutputQueue& operator=(const OutputQueue&) = delete;

  /// Queues bytes to write, in order; never blocks. Dropped once a write has failed.
  void push(std::string bytes);
  /// Bytes queued and not yet written.
  std::size_t pending_bytes() const;
  /// Waits until fewer than `bytes` are pending, a write failed, or `milliseconds` passed;
  /// true when below.
  bool wait_below(std::size_t bytes, int milliseconds);
  /// errno of the first failed write (EIO for a write of 0 bytes), 0 while none failed.
  int error() const;

  struct State;

 private:
  std::shared_ptr<State> state_;  // shared with the writer thread
};

}  // namespace bodyfmt::lsp
