#pragma once
/// The base protocol's framing: `Content-Length: N` headers, a blank line, then N bytes of
/// JSON. Reads from any byte chunks, so that a hostile stream (no header, a wrong length,
/// garbage, a length of a terabyte) costs an error reply and never a hang or a crash.

#include <cstddef>
#include <string>

namespace bodyfmt::lsp {

class MessageReader {
 public:
  /// Bodies above this are skipped (their bytes read and dropped) with an error.
  explicit MessageReader(std::size_t max_body_bytes = std::size_t{512} << 20) : max_body_(max_body_bytes) {}

  void feed(const char* data, std::size_t size);

  enum class Status { kMessage, kNeedMore, kBadFrame };
  /// The next complete message's body; kBadFrame with `error` for a header that is not the
  /// protocol's (the reader then looks for the next `Content-Length`), kNeedMore otherwise.
  Status next(std::string& body, std::string& error);

  /// True when a message was cut by the end of input.
  bool partial() const { return !buffer_.empty() || skip_ > 0 || body_length_ > 0; }

 private:
  std::string buffer_;
  std::size_t max_body_;
  std::size_t skip_ = 0;         ///< bytes of an oversized body still to drop
  std::size_t body_length_ = 0;  ///< the body being read (after its header), 0: reading a header
  bool in_body_ = false;
};

/// The frame of one outgoing message.
std::string frame(const std::string& body);

}  // namespace bodyfmt::lsp
