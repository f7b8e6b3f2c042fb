#include "serve.h"

#include "render.h"
#include "report.h"

#include <bodyfmt/text.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <iostream>
#include <list>
#include <map>
#include <memory>
#include <thread>

namespace bodyfmt::bodyview {
namespace {

// One thread, non-blocking sockets and poll(): no client can hold the server, another client,
// live reload or a signal for longer than one pass of the loop (kTick). A client gets kExchange
// to send its request and read the answer; beyond kMaxConnections the oldest is dropped.
using Clock = std::chrono::steady_clock;
constexpr auto kTick = std::chrono::milliseconds(100);
constexpr auto kExchange = std::chrono::seconds(10);
constexpr auto kWatchEvery = std::chrono::milliseconds(200);
constexpr std::size_t kMaxConnections = 32;
constexpr std::size_t kMaxRequest = 16384;
// Pipelined requests answered on one connection (all within its kExchange).
constexpr int kMaxRequestsPerConnection = 100;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

/// What identifies a version of a file: modification time and size (nullopt: missing).
using Stamp = std::pair<long long, long long>;
std::map<std::string, Stamp> stamps(const std::vector<std::string>& files) {
  std::map<std::string, Stamp> out;
  for (const std::string& f : files) {
    struct stat st {};
    if (::stat(f.c_str(), &st) == 0)
      out[f] = {static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec,
                static_cast<long long>(st.st_size)};
    else
      out[f] = {-1, -1};
  }
  return out;
}

struct Connection {
  int fd = -1;
  Clock::time_point deadline;
  std::string request;                      // what the client sent and was not answered yet
  std::string head;                         // the answer's status line and headers
  std::shared_ptr<const std::string> body;  // shared: the page is not copied per client
  std::size_t sent = 0;                     // of head, then body
  bool answering = false;
  bool keep_open = false;  // another request follows this answer on the connection
  int answered = 0;
};

struct Request {
  std::string method, target, host;
  bool close = false;  // Connection: close
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// The request line, the Host and the Connection header of one request's head (up to its
/// blank line, without the requests pipelined after it).
Request parse_request(const std::string& head) {
  Request r;
  const std::size_t line_end = head.find("\r\n");
  const std::string line = head.substr(0, line_end);
  const std::size_t a = line.find(' '), b = a == std::string::npos ? a : line.find(' ', a + 1);
  if (a == std::string::npos || b == std::string::npos) return r;
  r.method = line.substr(0, a);
  r.target = line.substr(a + 1, b - a - 1);
  for (std::size_t at = line_end; at != std::string::npos && at + 2 < head.size();) {
    const std::size_t start = at + 2, end = head.find("\r\n", start);
    const std::string field = head.substr(start, end == std::string::npos ? std::string::npos : end - start);
    const std::size_t colon = field.find(':');
    if (colon != std::string::npos && lower(field.substr(0, colon)) == "host") {
      std::string value = field.substr(colon + 1);
      value.erase(0, value.find_first_not_of(" \t"));
      value.erase(value.find_last_not_of(" \t") + 1);
      r.host = r.host.empty() ? value : std::string("\n");  // two Host headers: none is trusted
    }
    if (colon != std::string::npos && lower(field.substr(0, colon)) == "connection")
      r.close = r.close || lower(field.substr(colon + 1)).find("close") != std::string::npos;
    at = end;
  }
  return r;
}

void close_connection(Connection& c) {
  if (c.fd >= 0) ::close(c.fd);
  c.fd = -1;
}

}  // namespace

bool exit_with_lifeline(int fd) {
  // Readable, or its first read() would fail and be taken for the lifeline's end: a mistaken
  // FD (a write-only one, standard output) would end the server at once without a word.
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || (flags & O_ACCMODE) == O_WRONLY) return false;
  ::fcntl(fd, F_SETFD, FD_CLOEXEC);  // not for any program this one might start
  // A thread, not the serving loop's poll(): the first load may block (a slow disk, a FIFO)
  // before the loop runs. _exit rather than exit: the loop's state is the main thread's, and a
  // server that writes no file has nothing to flush.
  std::thread([fd] {
    char buffer[256];
    for (;;) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n == 0 || (n < 0 && errno != EINTR)) ::_exit(tools::kExitClean);
    }
  }).detach();
  return true;
}

int serve(tools::Front& front, const tools::Front::FilePolicy& policy, const std::string& path,
          const std::filesystem::path& assets, int port, bool verbose) {
  const int listener = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  int yes = 1;
  ::setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // never reachable from another machine
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  socklen_t length = sizeof address;
  if (listener < 0 || ::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(listener, 64) != 0 || ::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    front.print_error("--serve: cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + std::strerror(errno));
    return tools::kExitFatal;
  }
  struct sigaction action {};
  action.sa_handler = on_signal;  // no SA_RESTART: poll() returns at once
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
  const std::string port_text = std::to_string(ntohs(address.sin_port));
  // A DNS-rebinding page reaches this port under its own host name: only the loopback names
  // the URL can be spelled with are answered (the page holds absolute paths).
  const std::string hosts[] = {"127.0.0.1:" + port_text, "localhost:" + port_text, "[::1]:" + port_text};

  auto page = std::make_shared<const std::string>();  // the last good page
  std::string error_text;                             // the latest load's errors, shown over it
  long generation = 0;                                // of the page
  long attempt = 0;                                   // loads so far
  std::vector<std::string> watched{path};
  std::map<std::string, Stamp> seen;
  auto load = [&] {
    ++attempt;
    seen = stamps(watched);  // before the load: an edit during it is seen next time
    Rendered r = render(front, policy, path, assets, "/status");
    error_text.clear();
    TextOptions plain;
    for (const Diagnostic& d : r.diagnostics)
      if (d.severity == Severity::kFatal || d.severity == Severity::kError)
        error_text += format_text_diagnostic(d, front.sources(), plain);
    // A load that keeps the last good page shows its errors over it, but a failed first load
    // leaves no page: those are printed in full.
    if (r.page)
      report_page_findings(front, r.diagnostics, verbose, "http://127.0.0.1:" + port_text + "/");
    else
      front.print(r.diagnostics);
    if (r.page) {
      page = std::make_shared<const std::string>(std::move(*r.page));
      ++generation;
      watched = {path};
      for (const InputFile& f : r.inputs)
        if (f.path != path) watched.push_back(f.path);
      seen = stamps(watched);
    }
    std::cerr << "bodyview: load " << attempt << ": "
              << (r.page ? "page " + std::to_string(generation) : "kept the last good page")
              << (error_text.empty() ? "" : ", with errors") << std::endl;
  };
  load();
  if (page->empty()) return tools::kExitFatal;
  std::cout << "http://127.0.0.1:" << port_text << "/" << std::endl;

  // Answers the first request of c.request and takes it out: requests pipelined after it are
  // answered in turn, each parsed on its own (its own Host header), once this one is sent.
  auto answer = [&](Connection& c) {
    const std::size_t blank = c.request.find("\r\n\r\n");
    const std::size_t head_size = blank == std::string::npos ? c.request.size() : blank + 4;
    const Request r = parse_request(c.request.substr(0, head_size));
    c.request.erase(0, head_size);
    std::string status = "200 OK", type = "text/plain; charset=utf-8", extra;
    std::shared_ptr<const std::string> body;
    const bool known_host = std::find(std::begin(hosts), std::end(hosts), lower(r.host)) != std::end(hosts);
    if (r.method.empty()) {
      status = "400 Bad Request";
      body = std::make_shared<const std::string>("bad request\n");
    } else if (!known_host) {
      status = "421 Misdirected Request";
      body = std::make_shared<const std::string>("this server answers only http://127.0.0.1:" + port_text + "/\n");
    } else if (r.method != "GET" && r.method != "HEAD") {
      status = "405 Method Not Allowed";
      extra = "Allow: GET, HEAD\r\n";
      body = std::make_shared<const std::string>("only GET and HEAD\n");
    } else if (r.target == "/" || r.target.rfind("/?", 0) == 0) {
      type = "text/html; charset=utf-8";
      body = page;
    } else if (r.target == "/status") {
      type = "application/json";
      body = std::make_shared<const std::string>("{\"generation\":" + std::to_string(generation) +
                                                 ",\"attempt\":" + std::to_string(attempt) +
                                                 ",\"error\":" + text::json_quote(error_text) + "}");
    } else {
      status = "404 Not Found";
      body = std::make_shared<const std::string>("not found\n");
    }
    // The connection stays open only for a request already sent after this one (pipelined), and
    // only after a GET or HEAD from a loopback host: anything else may carry a body that is no request.
    c.keep_open = blank != std::string::npos && (status.rfind("200", 0) == 0 || status.rfind("404", 0) == 0) &&
                  !r.close && !c.request.empty() && ++c.answered < kMaxRequestsPerConnection;
    c.head = "HTTP/1.1 " + status + "\r\nContent-Type: " + type + "\r\n" + extra + "Cache-Control: no-store\r\n" +
             (c.keep_open ? "" : "Connection: close\r\n") + "Content-Length: " + std::to_string(body->size()) +
             "\r\n\r\n";
    c.body = r.method != "HEAD" ? std::move(body) : nullptr;
    c.sent = 0;
    c.answering = true;
  };
  auto has_request = [](const Connection& c) {
    return c.request.find("\r\n\r\n") != std::string::npos || c.request.size() > kMaxRequest;
  };

  std::list<Connection> connections;  // oldest first
  Clock::time_point next_watch = Clock::now() + kWatchEvery;
  std::vector<pollfd> fds;
  while (!g_stop) {
    fds.clear();
    fds.push_back({listener, POLLIN, 0});
    for (const Connection& c : connections) fds.push_back({c.fd, short(c.answering ? POLLOUT : POLLIN), 0});
    const int ready = ::poll(fds.data(), fds.size(), static_cast<int>(kTick.count()));
    if (g_stop) break;
    const Clock::time_point now = Clock::now();
    std::size_t k = 1;
    for (Connection& c : connections) {
      const short events = fds[k++].revents;
      if (ready > 0 && (events & (POLLERR | POLLNVAL))) {
        close_connection(c);
      } else if (ready > 0 && !c.answering && (events & (POLLIN | POLLHUP))) {
        char buffer[4096];
        const ssize_t n = ::recv(c.fd, buffer, sizeof buffer, 0);
        if (n <= 0) {
          if (n == 0 || (errno != EAGAIN && errno != EINTR)) close_connection(c);
        } else {
          c.request.append(buffer, static_cast<std::size_t>(n));
          if (has_request(c)) answer(c);
        }
      } else if (ready > 0 && c.answering && (events & POLLOUT)) {
        const std::string& part = c.sent < c.head.size() ? c.head : *c.body;
        const std::size_t from = c.sent < c.head.size() ? c.sent : c.sent - c.head.size();
        const ssize_t n = ::send(c.fd, part.data() + from, part.size() - from, MSG_NOSIGNAL);
        if (n < 0 && errno != EAGAIN && errno != EINTR) close_connection(c);
        if (n > 0) c.sent += static_cast<std::size_t>(n);
        if (c.sent == c.head.size() + (c.body ? c.body->size() : 0)) {
          if (!c.keep_open) {
            close_connection(c);
          } else {
            c.answering = false;
            if (has_request(c)) answer(c);
          }
        }
      }
      if (c.fd >= 0 && now > c.deadline) close_connection(c);  // slow to ask, or slow to read
    }
    connections.remove_if([](const Connection& c) { return c.fd < 0; });
    if (ready > 0 && (fds[0].revents & POLLIN)) {
      for (int client; (client = ::accept4(listener, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC)) >= 0;) {
        if (connections.size() >= kMaxConnections) {
          close_connection(connections.front());
          connections.pop_front();
        }
        Connection c;
        c.fd = client;
        c.deadline = now + kExchange;
        connections.push_back(std::move(c));
      }
    }
    if (now >= next_watch) {
      if (stamps(watched) != seen) load();
      next_watch = Clock::now() + kWatchEvery;
    }
  }
  for (Connection& c : connections) close_connection(c);
  ::close(listener);
  return tools::kExitClean;
}

}  // namespace bodyfmt::bodyview
