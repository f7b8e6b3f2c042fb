#include "serve.h"

#include "render.h"

#include <bodyfmt/text.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <iostream>
#include <map>

namespace bodyfmt::bodyview {
namespace {

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

void respond(int fd, const char* status, const char* type, const std::string& body) {
  std::string head =
      std::string("HTTP/1.1 ") + status + "\r\nContent-Type: " + type +
      "\r\nCache-Control: no-store\r\nConnection: close\r\nContent-Length: " + std::to_string(body.size()) + "\r\n\r\n";
  std::string all = head + body;
  for (std::size_t sent = 0; sent < all.size();) {
    const ssize_t n = ::send(fd, all.data() + sent, all.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<std::size_t>(n);
  }
}

/// The request target of a GET ("/" when it cannot be read).
std::string request_target(int fd) {
  std::string request;
  char buffer[2048];
  while (request.find("\r\n\r\n") == std::string::npos && request.size() < 16384) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 2000) <= 0) break;
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    request.append(buffer, static_cast<std::size_t>(n));
  }
  if (request.rfind("GET ", 0) != 0) return "";
  const std::size_t end = request.find(' ', 4);
  return request.substr(4, end == std::string::npos ? std::string::npos : end - 4);
}

}  // namespace

int serve(tools::Front& front, const tools::Front::FilePolicy& policy, const std::string& path,
          const std::filesystem::path& assets, int port) {
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  int yes = 1;
  ::setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // never reachable from another machine
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  socklen_t length = sizeof address;
  if (listener < 0 || ::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(listener, 16) != 0 || ::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    front.print_error("--serve: cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + std::strerror(errno));
    return tools::kExitFatal;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  std::string page;        // the last good page
  std::string error_text;  // the latest load's errors, shown over it
  long generation = 0;     // of the page
  long attempt = 0;        // loads so far
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
    front.print(r.diagnostics);
    if (r.page) {
      page = std::move(*r.page);
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
  if (page.empty()) return tools::kExitFatal;
  std::cout << "http://127.0.0.1:" << ntohs(address.sin_port) << "/" << std::endl;

  while (!g_stop) {
    pollfd p{listener, POLLIN, 0};
    const int ready = ::poll(&p, 1, 200);
    if (ready > 0) {
      const int client = ::accept(listener, nullptr, nullptr);
      if (client >= 0) {
        const std::string target = request_target(client);
        if (target == "/" || target.rfind("/?", 0) == 0) {
          respond(client, "200 OK", "text/html; charset=utf-8", page);
        } else if (target == "/status") {
          respond(client, "200 OK", "application/json",
                  "{\"generation\":" + std::to_string(generation) + ",\"attempt\":" + std::to_string(attempt) +
                      ",\"error\":" + text::json_quote(error_text) + "}");
        } else {
          respond(client, "404 Not Found", "text/plain", "not found\n");
        }
        ::close(client);
      }
    }
    if (stamps(watched) != seen) load();
  }
  ::close(listener);
  return tools::kExitClean;
}

}  // namespace bodyfmt::bodyview
