#include "framing.h"

#include <algorithm>
#include <cctype>
#include <optional>

namespace bodyfmt::lsp {

namespace {

constexpr std::size_t kMostHeaderBytes = 8192;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Where the next header may start after a bad one: the next "content-length" in `buffer`
/// from `from` on, else `fallback`.
std::size_t resync_point(const std::string& buffer, std::size_t fallback, std::size_t from = 1) {
  const std::size_t next = lower(buffer).find("content-length", from);
  return next != std::string::npos ? next : fallback;
}

}  // namespace

void MessageReader::feed(const char* data, std::size_t size) {
  if (skip_ > 0) {
    const std::size_t dropped = std::min(skip_, size);
    skip_ -= dropped;
    data += dropped;
    size -= dropped;
  }
  buffer_.append(data, size);
}

MessageReader::Status MessageReader::next(std::string& body, std::string& error) {
  if (skip_ > 0) return Status::kNeedMore;
  if (in_body_) {
    if (buffer_.size() < body_length_) return Status::kNeedMore;
    body.assign(buffer_, 0, body_length_);
    buffer_.erase(0, body_length_);
    in_body_ = false;
    body_length_ = 0;
    return Status::kMessage;
  }
  // A header block ends with an empty line ("\r\n\r\n"; a bare "\n\n" is accepted too).
  std::size_t end = buffer_.find("\r\n\r\n");
  std::size_t separator = 4;
  const std::size_t bare = buffer_.find("\n\n");
  if (bare != std::string::npos && (end == std::string::npos || bare < end)) end = bare, separator = 2;
  if (end == std::string::npos) {
    if (buffer_.size() <= kMostHeaderBytes) return Status::kNeedMore;
    error = "a header longer than " + std::to_string(kMostHeaderBytes) + " bytes";
    buffer_.erase(0, resync_point(buffer_, buffer_.size() - 14));
    return Status::kBadFrame;
  }
  const std::string header = buffer_.substr(0, end);
  std::optional<std::size_t> length;
  std::string problem;
  bool lengths_differ = false;
  for (std::size_t begin = 0; begin <= header.size();) {
    std::size_t stop = header.find('\n', begin);
    if (stop == std::string::npos) stop = header.size();
    std::string line = header.substr(begin, stop - begin);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    begin = stop + 1;
    if (line.empty()) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) {
      problem = "a header line without ':'";
      break;
    }
    if (lower(line.substr(0, colon)) != "content-length") continue;
    std::string value = line.substr(colon + 1);
    value.erase(0, value.find_first_not_of(" \t"));
    value.erase(value.find_last_not_of(" \t") + 1);
    if (value.empty() || value.size() > 18 ||
        !std::all_of(value.begin(), value.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      problem = "Content-Length is not a number";
      break;
    }
    const std::size_t this_length = std::stoull(value);
    // Two lengths: either may be the one the body has, and taking the wrong one would read
    // the next message into this one (or this one's tail as the next). The same length twice
    // is one length, as HTTP reads it.
    if (length && *length != this_length) {
      problem = "two different Content-Length headers";
      lengths_differ = true;
      break;
    }
    length = this_length;
  }
  if (problem.empty() && !length) problem = "no Content-Length header";
  if (!problem.empty()) {
    error = problem;
    // The next header after this one's block, not the second length inside it.
    buffer_.erase(0, lengths_differ ? resync_point(buffer_, end + separator, end + separator)
                                    : resync_point(buffer_, end + separator));
    return Status::kBadFrame;
  }
  buffer_.erase(0, end + separator);
  if (*length > max_body_) {
    error = "a message of " + std::to_string(*length) + " bytes, over the limit of " + std::to_string(max_body_);
    const std::size_t dropped = std::min<std::size_t>(*length, buffer_.size());
    buffer_.erase(0, dropped);
    skip_ = *length - dropped;
    return Status::kBadFrame;
  }
  in_body_ = true;
  body_length_ = *length;
  return next(body, error);
}

std::string frame(const std::string& body) {
  return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

}  // namespace bodyfmt::lsp
