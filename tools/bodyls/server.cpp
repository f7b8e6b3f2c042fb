#include "server.h"

#include "code_actions.h"
#include "feature_requests.h"
#include "framing.h"
#include "lsp_convert.h"
#include "message_json.h"
#include "model_check.h"
#include "output_queue.h"
#include "text_positions.h"
#include "uri.h"
#include "viewer_launcher.h"

#include <bodyfmt/file_cache.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>

#include <nlohmann/json.hpp>

#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#ifndef BODYFMT_VERSION
#define BODYFMT_VERSION "unknown"
#endif

namespace bodyfmt::lsp {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

namespace {

// JSON-RPC and LSP error codes.
constexpr int kParseError = -32700;
constexpr int kInvalidRequest = -32600;
constexpr int kMethodNotFound = -32601;
constexpr int kInvalidParams = -32602;
constexpr int kInternalError = -32603;
constexpr int kServerNotInitialized = -32002;
constexpr int kRequestCancelled = -32800;
constexpr int kRequestFailed = -32803;

std::string dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

bool process_alive(int pid) { return ::kill(pid, 0) == 0 || errno == EPERM; }

std::string canonical(const std::string& path) {
  std::error_code ec;
  const fs::path made = fs::weakly_canonical(path, ec);
  return ec ? path : made.string();
}

}  // namespace

struct Server::Impl {
  struct Document {
    std::string uri;
    std::string path;  ///< the name the loader gives the buffer (its file's path)
    int version = 0;
    std::string text;
    bool pending = false;
    Clock::time_point due;
    // The last check published.
    int checked_version = -1;
    /// Shared, never copied: a request for code actions takes it out of the lock, and a large
    /// model's findings are hundreds of megabytes.
    std::shared_ptr<const std::vector<Diagnostic>> findings = std::make_shared<std::vector<Diagnostic>>();
    std::shared_ptr<const Model> model;  ///< of the last text that loaded
    int model_version = -1;
    /// The other open buffers that model read as its included files, by canonical path.
    std::shared_ptr<const std::map<std::string, std::string>> model_texts;
    std::vector<std::string> dependencies;  ///< canonical paths of the files the model was read from
    std::map<std::string, fs::file_time_type> dependency_times;
    std::set<std::string> published_uris;
    /// The files its last check read: shared with the other documents', let go when it closes.
    std::shared_ptr<FileCache> file_cache;
  };

  tools::Front& front;
  ServerOptions options;
  Send send_raw;

  mutable std::mutex mutex;  // documents, contributions and the state below
  std::condition_variable wake;
  std::mutex send_mutex;
  std::map<std::string, Document> documents;  // by URI
  /// Diagnostics published on a URI, by the document whose check found them, each as its JSON
  /// text: a check's findings are converted once, and a publication is their concatenation, not
  /// a tree of JSON values copied for each step (280k findings cost gigabytes that way).
  std::map<std::string, std::map<std::string, std::vector<std::string>>> contributions;
  bool initialized = false;
  bool shutdown = false;
  bool exited = false;
  bool stopping = false;
  // While the messages of one read are handled, no check starts: a client's batch of edits is
  // one burst, whatever the scheduler does between two of its messages.
  bool reading_batch = false;
  int exit_code = 1;
  bool client_watches = false;
  bool client_disabled_actions = false;
  bool client_show_document = false;
  bool client_hover_plain_text = false;  ///< the client prefers plain text to Markdown in a hover
  // Requests are sent from the viewers' threads too.
  std::atomic<int> next_request_id{1};
  /// The client's process (initialize's processId), watched while it was alive at initialize.
  std::optional<int> client_process;
  std::set<std::string> cancelled;  // ids (dumped) of requests cancelled before they were handled
  Clock::time_point next_poll = Clock::now();
  std::thread worker;
  /// Meshes and included files as last read, while unchanged: a keystroke re-reads only the buffer.
  /// Each document has a cache that shares with this one and holds what its latest check used.
  std::shared_ptr<FileCache> file_cache = std::make_shared<FileCache>();
  ViewerLauncher viewers;

  Impl(tools::Front& f, ServerOptions o, Send s)
      : front(f), options(std::move(o)), send_raw(std::move(s)), viewers(options.bodyview_path) {}

  void send(const json& message) { send_text(dump(message)); }
  void send_text(const std::string& body) {
    std::lock_guard<std::mutex> lock(send_mutex);
    send_raw(body);
  }
  void respond(const json& id, json result) {
    send(json{{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}});
  }
  void respond_error(const json& id, int code, const std::string& message) {
    send(json{{"jsonrpc", "2.0"}, {"id", id}, {"error", {{"code", code}, {"message", message}}}});
  }
  void notify(const std::string& method, json params) {
    send(json{{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}});
  }
  void request(const std::string& method, json params) {
    json id = "bodyls-" + std::to_string(next_request_id++);
    send(json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", std::move(params)}});
  }

  // ---- messages -------------------------------------------------------------------------

  /// One message, as parse_message read it.
  void handle(MessageParse parsed, const json& message) {
    // Too deep to read safely: answered as a message that is not a request, whatever it holds.
    if (parsed == MessageParse::kTooDeep)
      return respond_error(nullptr, kInvalidRequest,
                           "the message nests more than " + std::to_string(kMostMessageDepth) + " arrays and objects");
    if (parsed == MessageParse::kNotJson) return respond_error(nullptr, kParseError, "the message is not JSON");
    if (!message.is_object()) return respond_error(nullptr, kInvalidRequest, "a message is a JSON object");
    const auto id_it = message.find("id");
    const bool has_id = id_it != message.end();
    json id = has_id ? *id_it : json();
    if (has_id && !id.is_number_integer() && !id.is_string())
      return respond_error(nullptr, kInvalidRequest, "an id is an integer or a string");
    const auto method_it = message.find("method");
    if (method_it == message.end()) return;  // a response to one of our requests: nothing waits for it
    if (!method_it->is_string()) return respond_error(has_id ? id : json(), kInvalidRequest, "method is not a string");
    const std::string method = *method_it;
    const json params = message.value("params", json::object());
    if (method == "exit") {
      std::lock_guard<std::mutex> lock(mutex);
      exited = true;
      exit_code = shutdown ? 0 : 1;
      stopping = true;
      wake.notify_all();
      return;
    }
    if (has_id) {
      if (cancelled.erase(dump(id)) > 0) return respond_error(id, kRequestCancelled, "cancelled");
      if (!initialized && method != "initialize")
        return respond_error(id, kServerNotInitialized, "the server is not initialized yet");
      if (shutdown) return respond_error(id, kInvalidRequest, "the server is shut down");
      try {
        std::optional<json> result = handle_request(method, params, id);
        if (!result) return respond_error(id, kMethodNotFound, "no method " + method);
        if (result->is_discarded()) return;  // answered later (answered_later)
        respond(id, std::move(*result));
      } catch (const std::invalid_argument& e) {
        respond_error(id, kRequestFailed, e.what());
      } catch (const json::exception& e) {
        respond_error(id, kInvalidParams, std::string("invalid params: ") + e.what());
      } catch (const std::exception& e) {
        respond_error(id, kInternalError, e.what());
      }
      return;
    }
    if (!initialized || shutdown) return;  // notifications are dropped then (LSP "initialize")
    try {
      handle_notification(method, params);
    } catch (const std::exception& e) {
      std::cerr << "bodyls: " << method << ": " << e.what() << '\n';
    }
  }

  std::optional<json> handle_request(const std::string& method, const json& params, const json& id) {
    if (method == "initialize") {
      if (initialized) throw std::runtime_error("initialize was already called");
      return initialize(params);
    }
    if (method == "shutdown") {
      {
        std::lock_guard<std::mutex> lock(mutex);
        shutdown = true;
      }
      viewers.end_all("bodyls is shutting down");
      return json(nullptr);
    }
    if (method == "textDocument/codeAction") return code_actions(params);
    if (method == "workspace/executeCommand") return execute_command(params, id);
    if (is_feature_method(method)) return feature_request(method, params);
    return std::nullopt;
  }

  void handle_notification(const std::string& method, const json& params) {
    if (method == "initialized") return on_initialized();
    if (method == "textDocument/didOpen") return did_open(params.at("textDocument"));
    if (method == "textDocument/didChange") return did_change(params);
    if (method == "textDocument/didClose") return did_close(params.at("textDocument").at("uri"));
    if (method == "textDocument/didSave") return did_save(params.at("textDocument").at("uri"));
    if (method == "workspace/didChangeWatchedFiles") return files_changed(params.at("changes"));
    // Unknown notifications (and $/ ones) are ignored, as the protocol says.
  }

  json initialize(const json& params) {
    const json capabilities = params.value("capabilities", json::object());
    const auto flag = [&](std::initializer_list<const char*> path) {
      const json* at = &capabilities;
      for (const char* key : path) {
        if (!at->is_object() || !at->contains(key)) return false;
        at = &(*at)[key];
      }
      return at->is_boolean() && at->get<bool>();
    };
    const json init = params.value("initializationOptions", json::object());
    std::lock_guard<std::mutex> lock(mutex);
    client_watches = flag({"workspace", "didChangeWatchedFiles", "dynamicRegistration"});
    client_disabled_actions = flag({"textDocument", "codeAction", "disabledSupport"});
    client_show_document = flag({"window", "showDocument", "support"});
    client_hover_plain_text = prefers_plain_text(capabilities, "hover");
    if (init.is_object() && init.contains("debounceMs") && init["debounceMs"].is_number_integer())
      options.debounce_ms = std::clamp(init["debounceMs"].get<int>(), 0, 10000);
    if (init.is_object() && init.contains("maxDiagnostics") && init["maxDiagnostics"].is_number_integer())
      options.max_published = std::clamp<long long>(init["maxDiagnostics"].get<long long>(), 1, 1000000);
    // A client in another process namespace names a process this one cannot see: only a process
    // alive now is watched, so that such a client is not taken for dead.
    if (params.contains("processId") && params["processId"].is_number_integer()) {
      const long long pid = params["processId"].get<long long>();
      if (pid > 0 && pid <= std::numeric_limits<int>::max() && process_alive(static_cast<int>(pid)))
        client_process = static_cast<int>(pid);
    }
    initialized = true;
    json sync = {{"openClose", true}, {"change", 2}, {"save", {{"includeText", false}}}};
    json capabilities_out = {
        {"positionEncoding", "utf-16"},
        {"textDocumentSync", sync},
        {"codeActionProvider", {{"codeActionKinds", {"quickfix", kUpgradeActionKind}}}},
        {"hoverProvider", true},
        {"completionProvider", {{"triggerCharacters", {":", " ", "*", "/"}}}},
        {"definitionProvider", true},
        {"referencesProvider", true},
        {"renameProvider", {{"prepareProvider", true}}},
        {"documentSymbolProvider", true},
        {"executeCommandProvider", {{"commands", {"bodyls.openViewer"}}}},
    };
    return json{{"capabilities", capabilities_out}, {"serverInfo", {{"name", "bodyls"}, {"version", BODYFMT_VERSION}}}};
  }

  void on_initialized() {
    if (!client_watches) return;
    // Every file: a model's meshes and included files may have any name and extension.
    json watchers = json::array({json{{"globPattern", "**/*"}}});
    request("client/registerCapability",
            {{"registrations", json::array({json{{"id", "bodyls-watch"},
                                                 {"method", "workspace/didChangeWatchedFiles"},
                                                 {"registerOptions", {{"watchers", watchers}}}}})}});
  }

  // ---- documents ------------------------------------------------------------------------

  void schedule(Document& d, Clock::time_point due) {
    d.pending = true;
    d.due = due;
    wake.notify_all();
  }
  Clock::time_point debounced() const { return Clock::now() + std::chrono::milliseconds(options.debounce_ms); }

  /// Documents whose model was read from `path` (canonical) get a new check.
  void schedule_dependents(const std::string& path, const std::string& except_uri) {
    for (auto& [uri, d] : documents) {
      if (uri == except_uri) continue;
      if (std::find(d.dependencies.begin(), d.dependencies.end(), path) != d.dependencies.end())
        schedule(d, debounced());
    }
  }

  void did_open(const json& item) {
    const std::string uri = item.at("uri");
    std::lock_guard<std::mutex> lock(mutex);
    Document& d = documents[uri];
    d = Document{};
    d.uri = uri;
    d.path = path_from_uri(uri).value_or(uri);
    d.version = item.value("version", 0);
    d.text = item.at("text").get<std::string>();
    d.file_cache = file_cache->make_sharing();
    schedule(d, Clock::now());  // the first check without a debounce
    schedule_dependents(canonical(d.path), uri);
  }

  void did_change(const json& params) {
    const json& item = params.at("textDocument");
    const std::string uri = item.at("uri");
    std::lock_guard<std::mutex> lock(mutex);
    auto it = documents.find(uri);
    if (it == documents.end()) return;
    Document& d = it->second;
    // The debounce holds back only edits that come faster than their checks (a key held down, a
    // paste in pieces, a client's batch, typing in a model whose check takes longer than a
    // keystroke): an edit made while the last text's findings are published is checked at
    // once, so that its findings take the check's time and no more; one made while a check is
    // pending or running waits until debounce_ms after it. Either way a newer edit supersedes.
    const bool idle = !d.pending && d.checked_version == d.version;
    for (const json& change : params.at("contentChanges")) {
      const std::string& text = change.at("text").get_ref<const std::string&>();
      if (change.contains("range")) {
        apply_change(d.text, range_from_json(change["range"]), text);
      } else {
        d.text = text;
      }
    }
    d.version = item.value("version", d.version + 1);
    schedule(d, idle ? Clock::now() : debounced());
    schedule_dependents(canonical(d.path), uri);
  }

  void did_close(const std::string& uri) {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = documents.find(uri);
    if (it == documents.end()) return;
    const std::string path = canonical(it->second.path);
    const std::set<std::string> uris = it->second.published_uris;
    documents.erase(it);
    for (const std::string& u : uris) {
      contributions[u].erase(uri);
      publish_union(u, std::nullopt);
    }
    schedule_dependents(path, uri);
  }

  void did_save(const std::string& uri) {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = documents.find(uri);
    if (it != documents.end()) schedule_dependents(canonical(it->second.path), uri);
  }

  void files_changed(const json& changes) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const json& change : changes) {
      const auto path = path_from_uri(change.at("uri"));
      if (path) schedule_dependents(canonical(*path), "");
    }
  }

  /// The server's own watch, for clients without didChangeWatchedFiles: every poll_ms, the
  /// modification times of each document's dependency files.
  void poll_dependencies() {
    for (auto& [uri, d] : documents) {
      bool changed = false;
      for (auto& [path, time] : d.dependency_times) {
        std::error_code ec;
        const fs::file_time_type now = fs::last_write_time(path, ec);
        if (now != time) changed = true, time = now;
      }
      if (changed) schedule(d, Clock::now());
    }
  }

  // ---- checks -----------------------------------------------------------------------------

  struct Snapshot {
    std::string uri, path, text;
    int version = 0;
    std::map<std::string, std::string> other_texts;  // canonical path -> buffer
    std::shared_ptr<FileCache> file_cache;           // the document's
  };

  /// Takes the next due document (the lock held); nullopt when none is due by `now`.
  std::optional<Snapshot> take_due(Clock::time_point now, bool ignore_due) {
    Document* next = nullptr;
    for (auto& [uri, d] : documents)
      if (d.pending && (ignore_due || d.due <= now) && (!next || d.due < next->due)) next = &d;
    if (!next) return std::nullopt;
    next->pending = false;
    Snapshot s{next->uri, next->path, next->text, next->version, {}, next->file_cache};
    for (const auto& [uri, d] : documents)
      if (&d != next && d.path != d.uri) s.other_texts[canonical(d.path)] = d.text;
    return s;
  }

  void check_and_publish(const Snapshot& s) {
    tools::ModelInput input;
    input.path = s.path;
    input.name = s.path;
    input.text = s.text;
    input.read_by_front = true;
    tools::ModelCheck result;
    if (auto policy = front.policy_for(s.path)) {
      LoadOptions load = front.load_options();
      load.file_texts = s.other_texts;
      load.file_cache = s.file_cache;
      result = tools::check_model_input(load, input, policy->options, {true, true});
      // A text that did not load read less than the document uses: its cache keeps what it had.
      if (result.loaded) s.file_cache->forget_unused();
    } else {
      result.diagnostics.push_back(make_diagnostic(
          "config-invalid", SourceLocation{s.path, 1, 1},
          "the .bodycheck.yaml that applies to this file is malformed (bodycheck prints its errors); not checked"));
    }
    tools::sort_unique_findings(result.diagnostics);
    std::vector<std::string> dependencies;
    for (const InputFile& f : result.inputs) dependencies.push_back(canonical(f.path));
    // Converted before the lock is taken: requests are answered while a large check's findings
    // are turned into the protocol's terms.
    std::map<std::string, std::vector<std::string>> by_uri =
        published_by_uri(result.diagnostics, s, options.max_published);

    std::lock_guard<std::mutex> lock(mutex);
    auto it = documents.find(s.uri);
    // A newer edit (or a close) supersedes this check: its findings are never published.
    if (it == documents.end() || it->second.version != s.version || it->second.text != s.text) return;
    Document& d = it->second;
    d.checked_version = s.version;
    if (result.model) {
      d.model = result.model;
      d.model_version = s.version;
      auto texts = std::make_shared<std::map<std::string, std::string>>();
      for (const std::string& path : dependencies)
        if (auto open = s.other_texts.find(path); open != s.other_texts.end()) texts->insert(*open);
      d.model_texts = std::move(texts);
    }
    if (result.loaded) {
      d.dependencies = dependencies;
      d.dependency_times.clear();
      for (const std::string& path : dependencies) {
        std::error_code ec;
        if (path != canonical(d.path)) d.dependency_times[path] = fs::last_write_time(path, ec);
      }
    }
    d.findings = std::make_shared<const std::vector<Diagnostic>>(std::move(result.diagnostics));
    std::set<std::string> uris = d.published_uris;
    for (const auto& [uri, list] : by_uri) uris.insert(uri);
    uris.insert(d.uri);
    d.published_uris.clear();
    for (const std::string& uri : uris) {
      auto found = by_uri.find(uri);
      if (found != by_uri.end()) {
        contributions[uri][d.uri] = std::move(found->second);
        d.published_uris.insert(uri);
      } else {
        contributions[uri].erase(d.uri);
      }
      publish_union(uri, uri == d.uri ? std::optional<int>(s.version) : std::nullopt);
    }
  }

  /// The findings of one check as JSON texts by the URI of their file, at most `most` of them:
  /// beyond it, errors are kept before warnings and warnings before notes, and the document gets
  /// one more finding that says how many are not shown and where to see them all. An editor
  /// cannot show 280,000 findings usefully, and a message of that size holds the client up.
  std::map<std::string, std::vector<std::string>> published_by_uri(const std::vector<Diagnostic>& findings,
                                                                   const Snapshot& s, std::size_t most) const {
    std::vector<const Diagnostic*> shown;
    shown.reserve(std::min(findings.size(), most));
    if (findings.size() <= most) {
      for (const Diagnostic& f : findings) shown.push_back(&f);
    } else {
      for (const Severity level : {Severity::kFatal, Severity::kError, Severity::kWarning, Severity::kNote})
        for (const Diagnostic& f : findings)
          if (f.severity == level && shown.size() < most) shown.push_back(&f);
      std::sort(shown.begin(), shown.end());  // back in the findings' order (they are one vector)
    }
    FileTexts texts(s.path, s.uri, s.text, s.other_texts);
    std::map<std::string, std::vector<std::string>> by_uri;
    for (const Diagnostic* f : shown)
      by_uri[texts.uri(f->location.file.str())].push_back(dump(diagnostic_to_json(*f, texts)));
    if (shown.size() < findings.size()) {
      const std::size_t hidden = findings.size() - shown.size();
      Diagnostic more = make_diagnostic("lsp-findings-limited", SourceLocation{s.path, 1, 1},
                                        std::to_string(hidden) +
                                            " more findings of this check are not shown (the server shows at most " +
                                            std::to_string(most) + ", errors first); `bodycheck " + s.path +
                                            "` lists all " + std::to_string(findings.size()));
      by_uri[s.uri].push_back(dump(diagnostic_to_json(more, texts)));
    }
    return by_uri;
  }

  /// Publishes the union of what every open document found in `uri` (the lock held). The
  /// message is queued, never written here: the lock is never held while the client reads.
  void publish_union(const std::string& uri, std::optional<int> version) {
    std::string list;
    std::set<std::string_view> seen;  // a file included by two open models reports a finding once
    auto& from_documents = contributions[uri];
    for (const auto& [from, texts] : from_documents)
      for (const std::string& d : texts)
        if (seen.insert(d).second) {
          if (!list.empty()) list += ',';
          list += d;
        }
    std::string message = R"({"jsonrpc":"2.0","method":"textDocument/publishDiagnostics","params":{"diagnostics":[)";
    message += list;
    message += R"(],"uri":)" + dump(json(uri));
    if (version) message += R"(,"version":)" + std::to_string(*version);
    message += "}}";
    if (from_documents.empty()) contributions.erase(uri);
    send_text(message);
  }

  void run_pending_checks() {
    for (;;) {
      std::optional<Snapshot> s;
      {
        std::lock_guard<std::mutex> lock(mutex);
        s = take_due(Clock::now(), true);
      }
      if (!s) return;
      check_and_publish(*s);
    }
  }

  void worker_loop() {
    std::unique_lock<std::mutex> lock(mutex);
    while (!stopping) {
      const Clock::time_point now = Clock::now();
      if (!client_watches && now >= next_poll) {
        poll_dependencies();
        next_poll = now + std::chrono::milliseconds(options.poll_ms);
      }
      std::optional<Snapshot> s;
      if (!reading_batch) s = take_due(now, false);
      if (s) {
        lock.unlock();
        check_and_publish(*s);
        lock.lock();
        continue;
      }
      Clock::time_point until = client_watches ? now + std::chrono::hours(1) : next_poll;
      if (!reading_batch)  // else the batch's end wakes us
        for (const auto& [uri, d] : documents)
          if (d.pending) until = std::min(until, d.due);
      wake.wait_until(lock, until);
    }
  }

  // ---- code actions, features, commands --------------------------------------------------

  json code_actions(const json& params) {
    const std::string uri = params.at("textDocument").at("uri");
    CodeActionQuery query;
    query.range = range_from_json(params.at("range"));
    const json context = params.value("context", json::object());
    if (context.contains("only")) query.only = context["only"].get<std::vector<std::string>>();
    std::unique_lock<std::mutex> lock(mutex);
    query.disabled_support = client_disabled_actions;
    auto it = documents.find(uri);
    // Fix-its are byte offsets in the text checked: none for a text not checked yet.
    if (it == documents.end() || it->second.checked_version != it->second.version) return json::array();
    const Document& d = it->second;
    if (d.model && d.model_version == d.version) query.model = d.model;
    // Out of the lock, so that the actions (a link's shapes integrated) never hold up the checks.
    const std::string path = d.path, text = d.text;
    const std::shared_ptr<const std::vector<Diagnostic>> findings = d.findings;
    lock.unlock();
    return code_actions_for(uri, path, text, *findings, query);
  }

  std::optional<json> feature_request(const std::string& method, const json& params) {
    FeatureDocument document;
    {
      std::lock_guard<std::mutex> lock(mutex);
      auto it = documents.find(params.at("textDocument").at("uri").get<std::string>());
      if (it == documents.end()) throw std::invalid_argument("the document is not open");
      const Document& d = it->second;
      document =
          FeatureDocument{d.uri, d.path, d.text, d.model, d.model && d.model_version == d.version, d.model_texts};
      document.plain_text = client_hover_plain_text;
    }
    return answer_feature(method, params, document);
  }

  /// A request's result that says its answer is sent later, from another thread.
  static json answered_later() { return json(json::value_t::discarded); }
  json execute_command(const json& params, const json& id);
};

json Server::Impl::execute_command(const json& params, const json& id) {
  const std::string command = params.at("command");
  if (command != "bodyls.openViewer") throw std::invalid_argument("no command " + command);
  // arguments: [the document's URI]
  const json arguments = params.value("arguments", json::array());
  if (!arguments.is_array() || arguments.empty() || !arguments[0].is_string())
    throw json::type_error::create(302, "bodyls.openViewer takes the document's URI", &arguments);
  const std::string uri = arguments[0];
  const std::optional<std::string> path = path_from_uri(uri);
  if (!path) throw std::invalid_argument("bodyls.openViewer: not a file: " + uri);
  // A viewer takes seconds to start (a minute at most): it is answered when it serves, from the
  // thread that waits for it, and every other message is handled meanwhile.
  const auto answer = [this, id, file = *path](const std::optional<std::string>& url, const std::string& why) {
    if (!url) return respond_error(id, kRequestFailed, "bodyls.openViewer: " + why);
    bool show = false;
    {
      std::lock_guard<std::mutex> lock(mutex);
      show = client_show_document;
    }
    if (show)
      request("window/showDocument", {{"uri", *url}, {"external", true}});
    else
      notify("window/showMessage", {{"type", 3}, {"message", "bodyview serves " + file + " at " + *url}});
    respond(id, json{{"url", *url}});
  };
  std::string ended;
  viewers.open(*path, answer, ended);
  if (!ended.empty())
    notify("window/showMessage", {{"type", 3},
                                  {"message", "bodyls ended the viewer of " + ended + ": at most " +
                                                  std::to_string(ViewerLauncher::kMostViewers) +
                                                  " run at once, and it was the least recently opened"}});
  return answered_later();
}

Server::Server(tools::Front& front, ServerOptions options, Send send)
    : impl_(std::make_unique<Impl>(front, std::move(options), std::move(send))) {
  if (impl_->options.threaded) impl_->worker = std::thread([this] { impl_->worker_loop(); });
}

Server::~Server() {
  impl_->viewers.end_all("");  // at once: the check under way may take a while to end
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->stopping = true;
    impl_->wake.notify_all();
  }
  if (impl_->worker.joinable()) impl_->worker.join();
}

void Server::handle_batch(const std::vector<std::string>& bodies) {
  struct HoldChecks {
    Impl& impl;
    explicit HoldChecks(Impl& i) : impl(i) { set(true); }
    ~HoldChecks() { set(false); }
    void set(bool hold) {
      std::lock_guard<std::mutex> lock(impl.mutex);
      impl.reading_batch = hold;
      if (!hold) impl.wake.notify_all();
    }
  } hold(*impl_);
  // Each body is parsed once, here (parse_message bounds its depth).
  std::vector<std::pair<MessageParse, json>> messages(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) messages[i].first = parse_message(bodies[i], messages[i].second);
  // Cancellations first: a request cancelled in the same read, after it, is answered as
  // cancelled. One pass with the ids of the requests read so far: linear in the batch.
  std::set<std::string> requested;
  for (const auto& [parsed, message] : messages) {
    if (parsed != MessageParse::kOk || !message.is_object() || !message.contains("method")) continue;
    if (message["method"] == "$/cancelRequest") {
      const auto params = message.find("params");
      if (params != message.end() && params->is_object() && params->contains("id") &&
          requested.count(dump((*params)["id"])) > 0)
        impl_->cancelled.insert(dump((*params)["id"]));
    } else if (message.contains("id")) {
      requested.insert(dump(message["id"]));
    }
  }
  for (const auto& [parsed, message] : messages) {
    if (exited()) return;
    impl_->handle(parsed, message);
  }
  impl_->cancelled.clear();
}

void Server::handle(const std::string& body) { handle_batch({body}); }

void Server::bad_frame(const std::string& why) {
  impl_->respond_error(nullptr, kParseError, "bad message frame: " + why);
}

void Server::run_pending_checks() { impl_->run_pending_checks(); }

std::optional<int> Server::client_process() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->client_process;
}

void Server::end_viewers() { impl_->viewers.end_all("bodyls is exiting"); }

bool Server::exited() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->exited;
}

int Server::exit_code() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->exit_code;
}

// Where a user finds the set-ups that start bodyls (CMake installs editors/ there).
const char* const kEditorSetups =
    "Editor set-ups (Neovim, Emacs, VS Code, Kate; how to load each: docs/tools/bodyls.md, \"Editors\"): "
    "editors/ in the source tree, share/bodyfmt/editors where bodyfmt is installed. They start the bodyls on PATH.";

int run_server(int argc, char** argv) {
  tools::Front front("bodyls",
                     "The language server for Choreonoid .body files (LSP over standard input and output); the "
                     "options are bodycheck's",
                     {true, false});
  front.app().footer(kEditorSetups);
  // The editor sends the files: no positional paths (the front's are bodycheck's).
  front.app().remove_option(front.app().get_option("paths"));
  ServerOptions options;
  bool stdio = false;
  front.app().add_flag("--stdio", stdio, "talk over standard input and output (the default; editors pass it)");
  front.app()
      .add_option("--debounce-ms", options.debounce_ms,
                  "an edit made while a check is pending or running is checked this long after it (default 50); "
                  "an edit made while the findings are up to date is checked at once")
      ->check(CLI::Range(0, 10000));
  front.app().add_option("--bodyview", options.bodyview_path,
                         "the bodyview program that bodyls.openViewer starts (default: the one beside bodyls)");
  if (auto code = front.parse(argc, argv)) return *code;
  // A client that closes its end of the pipe would kill the process by SIGPIPE at the next
  // write, before it says anything or ends its viewers: with the signal ignored, the write
  // fails with EPIPE and takes the path below.
  ::signal(SIGPIPE, SIG_IGN);
  // Every message goes through the writer's queue: neither this thread nor the checking one
  // ever waits for the client to read (output_queue.h).
  OutputQueue output(STDOUT_FILENO);
  Server server(front, options, [&output](const std::string& body) { output.push(frame(body)); });
  // While the client has not read this much, its next messages wait: its requests would only
  // queue more replies. The session still ends when its input ends or it dies.
  constexpr std::size_t kMostUnread = std::size_t{64} << 20;
  MessageReader reader;
  std::vector<char> buffer(1 << 16);
  bool client_gone = false;
  while (!server.exited() && !output.error()) {
    // Woken every 200 ms: a write that failed on the writer thread, or a client process that
    // died without closing the pipe, ends the session without waiting for another message.
    if (const std::optional<int> pid = server.client_process(); pid && !process_alive(*pid)) {
      client_gone = true;
      break;
    }
    if (output.pending_bytes() >= kMostUnread) {
      // Only whether the client closed its end is looked at, not its messages.
      pollfd input{STDIN_FILENO, 0, 0};
      if (::poll(&input, 1, 0) > 0 && (input.revents & (POLLHUP | POLLERR | POLLNVAL))) break;
      output.wait_below(kMostUnread, 200);
      continue;
    }
    pollfd input{STDIN_FILENO, POLLIN, 0};
    const int ready = ::poll(&input, 1, 200);
    if (ready == 0 || (ready < 0 && errno == EINTR)) continue;
    const ssize_t n = ::read(STDIN_FILENO, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    reader.feed(buffer.data(), static_cast<std::size_t>(n));
    std::vector<std::string> bodies;
    for (;;) {
      std::string body, error;
      const MessageReader::Status status = reader.next(body, error);
      if (status == MessageReader::Status::kNeedMore) break;
      if (status == MessageReader::Status::kBadFrame) {
        server.handle_batch(bodies);
        bodies.clear();
        server.bad_frame(error);
        continue;
      }
      bodies.push_back(std::move(body));
    }
    server.handle_batch(bodies);
  }
  int code = server.exited() ? server.exit_code() : 1;  // the end of input: an exit without shutdown
  // What is queued is the session's last word (the reply to `shutdown`, the findings of the last
  // check): given a second to be written, never waited for longer. Its write may be the one that
  // fails (a full disk): the error is looked at after it.
  if (!client_gone) output.wait_below(1, 1000);
  if (const int error = output.error()) {
    front.print_error(std::string("cannot write to standard output: ") + std::strerror(error));
    code = tools::kExitFatal;
  } else if (client_gone) {
    front.print_error("the client's process " + std::to_string(*server.client_process()) +
                      " has ended; so does this session");
  }
  server.end_viewers();
  // A check still running (a large model takes seconds) and a writer blocked on a client that
  // stopped reading are not waited for: the process ends here, with the session's code.
  std::cerr.flush();
  std::_Exit(code);
}

}  // namespace bodyfmt::lsp
