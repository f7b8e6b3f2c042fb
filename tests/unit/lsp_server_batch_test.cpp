// bodyls's threaded server: the messages of one read are one burst. An edit made while the
// findings are up to date is checked at once, but not before the rest of its read is handled,
// so an edit later in the same read supersedes it and its findings are never published, however
// long the server takes between two messages of the batch (here: a reply the client is slow to
// take, 1 s, long enough for any check of this model).
#include "server.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace {

using json = nlohmann::json;

bodyfmt::tools::Front& test_front() {
  static bodyfmt::tools::Front* front = [] {
    auto* made = new bodyfmt::tools::Front("bodyls", "", {true, false});
    const char* argv[] = {"bodyls", "--no-meshes"};
    REQUIRE_FALSE(made->parse(2, const_cast<char**>(argv)));
    return made;
  }();
  return *front;
}

const char* const kModel =
    "format: ChoreonoidBody\nformat_version: 2.0\nname: B\nroot_link: BASE\nlinks:\n"
    "  - { name: BASE, joint_type: free, mass: 1, inertia: [1,0,0,0,1,0,0,0,1] }\n";

class Client {
 public:
  std::vector<json> received() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }
  void take(const std::string& body) {
    json message = json::parse(body);
    // The reply to request 99 is slow to leave: the reader thread is held here, mid-batch.
    if (message.value("id", json()) == 99) std::this_thread::sleep_for(std::chrono::seconds(1));
    std::lock_guard<std::mutex> lock(mutex_);
    received_.push_back(std::move(message));
    arrived_.notify_all();
  }
  /// Waits (up to 30 s) for diagnostics published for `version`.
  bool wait_for_version(int version) {
    std::unique_lock<std::mutex> lock(mutex_);
    return arrived_.wait_for(lock, std::chrono::seconds(30), [&] {
      for (const json& m : received_)
        if (m.value("method", "") == "textDocument/publishDiagnostics" && m["params"].value("version", -1) == version)
          return true;
      return false;
    });
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<json> received_;
};

std::string message(const std::string& method, json params, json id = nullptr) {
  json m{{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}};
  if (!id.is_null()) m["id"] = id;
  return m.dump();
}

std::string append_comment(const std::string& uri, int version) {
  const json at{{"line", 6}, {"character", 0}};
  return message("textDocument/didChange",
                 {{"textDocument", {{"uri", uri}, {"version", version}}},
                  {"contentChanges", json::array({{{"range", {{"start", at}, {"end", at}}}, {"text", "# edit\n"}}})}});
}

}  // namespace

TEST_CASE("lsp server: no check starts while one read's messages are handled") {
  Client client;
  bodyfmt::lsp::ServerOptions options;
  options.threaded = true;
  options.debounce_ms = 300;
  const std::string uri = "file:///nonexistent/bodyls_batch/model.body";
  std::vector<json> received;
  {
    bodyfmt::lsp::Server server(test_front(), options, [&client](const std::string& body) { client.take(body); });
    server.handle(message("initialize", {{"capabilities", json::object()}}, 1));
    server.handle(message("initialized", json::object()));
    server.handle(
        message("textDocument/didOpen",
                {{"textDocument", {{"uri", uri}, {"languageId", "body"}, {"version", 1}, {"text", kModel}}}}));
    REQUIRE(client.wait_for_version(1));
    // Version 2 finds the findings up to date; the unknown request 99 between it and version 3
    // holds the reader for a second.
    server.handle_batch(
        {append_comment(uri, 2), message("bodyls/noSuchRequest", json::object(), 99), append_comment(uri, 3)});
    REQUIRE(client.wait_for_version(3));
    received = client.received();
  }
  std::vector<int> versions;
  for (const json& m : received)
    if (m.value("method", "") == "textDocument/publishDiagnostics")
      versions.push_back(m["params"].value("version", -1));
  std::string listed;
  for (int v : versions) listed += " " + std::to_string(v);
  INFO("diagnostics published for versions" << listed);
  CHECK(versions == std::vector<int>{1, 3});
  bool answered = false;
  for (const json& m : received) answered = answered || (m.value("id", json()) == 99 && m.contains("error"));
  CHECK(answered);
}
