// libFuzzer target: bodyls under random edits (issue 38). A session opens a corpus model and
// makes random edits (inserts, deletes, pastes of another model's text) at random UTF-8 byte
// offsets and UTF-16 positions (inside surrogate pairs, past line ends, past the last line),
// with checks and requests in between, all in-process and synchronous (no threads). Oracles:
// no published position lies outside the document it was published for, every edit of a code
// action lies inside the document, and the last diagnostics equal a fresh session's on the
// final text. The fuzzer keeps its own copy of the text, edited by its own UTF-16 rules.
#include "server.h"

#include <fuzzer/FuzzedDataProvider.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#ifndef BODYFMT_SHARED_DIR
#define BODYFMT_SHARED_DIR ""
#endif
#ifndef BODYFMT_EXAMPLES_DIR
#define BODYFMT_EXAMPLES_DIR ""
#endif

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

struct Model {
  std::string path;
  std::string text;
};

/// Valid UTF-8 (invalid bytes as U+FFFD): a client's text always is, as JSON's strings are.
std::string valid_utf8(const std::string& in) {
  std::string out;
  for (std::size_t i = 0; i < in.size();) {
    const auto c = static_cast<unsigned char>(in[i]);
    std::size_t n = c < 0x80                   ? 1
                    : (c >= 0xC2 && c <= 0xDF) ? 2
                    : (c >= 0xE0 && c <= 0xEF) ? 3
                    : (c >= 0xF0 && c <= 0xF4) ? 4
                                               : 0;
    bool ok = n > 0 && i + n <= in.size();
    unsigned code = n == 1 ? c : n == 2 ? c & 0x1F : n == 3 ? c & 0x0F : c & 0x07;
    for (std::size_t k = 1; ok && k < n; ++k) {
      ok = (static_cast<unsigned char>(in[i + k]) & 0xC0) == 0x80;
      code = (code << 6) | (static_cast<unsigned char>(in[i + k]) & 0x3F);
    }
    const unsigned minimum = n == 2 ? 0x80 : n == 3 ? 0x800 : n == 4 ? 0x10000 : 0;
    if (ok && code >= minimum && !(code >= 0xD800 && code <= 0xDFFF) && code <= 0x10FFFF) {
      out.append(in, i, n);
      i += n;
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

const std::vector<Model>& models() {
  static const std::vector<Model> all = [] {
    std::vector<Model> found;
    for (const std::string root :
         {std::string(BODYFMT_EXAMPLES_DIR), std::string(BODYFMT_SHARED_DIR) + "/corpus/choreonoid"}) {
      std::error_code ec;
      for (fs::recursive_directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
        if (it->path().extension() != ".body" || !it->is_regular_file(ec) || it->file_size(ec) > 64 * 1024) continue;
        std::ifstream in(it->path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        found.push_back({it->path().string(), valid_utf8(text.str())});
      }
    }
    std::sort(found.begin(), found.end(), [](const Model& a, const Model& b) { return a.path < b.path; });
    if (found.empty()) found.push_back({"/fuzz/model.body", "format: ChoreonoidBody\nlinks: []\n"});
    return found;
  }();
  return all;
}

bodyfmt::tools::Front& front() {
  static bodyfmt::tools::Front* f = [] {
    auto* made = new bodyfmt::tools::Front("fuzz_lsp", "", {true, false});
    const char* argv[] = {"fuzz_lsp", "--no-meshes", "--max-yaml-nodes", "200000", "--max-yaml-depth", "64"};
    if (made->parse(6, const_cast<char**>(argv))) std::abort();
    return made;
  }();
  return *f;
}

// ---- the fuzzer's own text rules (independent of bodyls's text_positions) ------------------

struct Line {
  std::size_t begin, end;  // bytes, without the line break
};

std::vector<Line> lines_of(const std::string& text) {
  std::vector<Line> lines;
  std::size_t begin = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n' || text[i] == '\r') {
      lines.push_back({begin, i});
      if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      begin = i + 1;
    }
  }
  lines.push_back({begin, text.size()});
  return lines;
}

std::size_t char_bytes(unsigned char c) { return c < 0x80 ? 1 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : 4; }

/// UTF-16 units of the (valid UTF-8) bytes [begin, end).
int units(const std::string& text, std::size_t begin, std::size_t end) {
  int n = 0;
  for (std::size_t i = begin; i < end; i += char_bytes(static_cast<unsigned char>(text[i])))
    n += char_bytes(static_cast<unsigned char>(text[i])) == 4 ? 2 : 1;
  return n;
}

/// The protocol's position -> byte offset, clamped as the protocol says (a line past the end:
/// the text's end; a character past the line: its end; inside a surrogate pair: before it).
std::size_t offset_of(const std::string& text, int line, int character) {
  const std::vector<Line> lines = lines_of(text);
  if (line >= static_cast<int>(lines.size())) return text.size();
  const Line l = lines[static_cast<std::size_t>(line)];
  std::size_t i = l.begin;
  int u = 0;
  while (i < l.end) {
    const std::size_t n = char_bytes(static_cast<unsigned char>(text[i]));
    const int w = n == 4 ? 2 : 1;
    if (u + w > character) break;
    u += w;
    i += n;
  }
  return i;
}

std::pair<int, int> position_of(const std::string& text, std::size_t offset) {
  const std::vector<Line> lines = lines_of(text);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (offset <= lines[k].end || k + 1 == lines.size()) {
      std::size_t at = std::min(std::max(offset, lines[k].begin), lines[k].end);
      while (at > lines[k].begin && (static_cast<unsigned char>(text[at]) & 0xC0) == 0x80) --at;
      return {static_cast<int>(k), units(text, lines[k].begin, at)};
    }
    if (offset < lines[k + 1].begin) return {static_cast<int>(k), units(text, lines[k].begin, lines[k].end)};
  }
  return {0, 0};
}

bool inside(const std::string& text, const json& position) {
  const std::vector<Line> lines = lines_of(text);
  const int line = position.at("line"), character = position.at("character");
  if (line < 0 || line >= static_cast<int>(lines.size()) || character < 0) return false;
  const Line l = lines[static_cast<std::size_t>(line)];
  return character <= units(text, l.begin, l.end);
}

void check_range(const std::string& text, const json& range, const char* what) {
  if (!inside(text, range.at("start")) || !inside(text, range.at("end"))) {
    std::fprintf(stderr, "%s outside the document: %s\n", what, range.dump().c_str());
    std::abort();
  }
}

// ---- a session ----------------------------------------------------------------------------

struct Session {
  std::vector<json> sent;
  bodyfmt::lsp::Server server;
  int next_id = 1;
  Session() : server(front(), options(), [this](const std::string& body) { sent.push_back(json::parse(body)); }) {}
  static bodyfmt::lsp::ServerOptions options() {
    bodyfmt::lsp::ServerOptions o;
    o.threaded = false;
    return o;
  }
  void notify(const std::string& method, json params) {
    server.handle(json{{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}}.dump());
  }
  json request(const std::string& method, json params) {
    const int id = next_id++;
    server.handle(json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", std::move(params)}}.dump());
    for (auto it = sent.rbegin(); it != sent.rend(); ++it)
      if (it->contains("id") && (*it)["id"] == id) return *it;
    std::fprintf(stderr, "no answer to %s\n", method.c_str());
    std::abort();
  }
  void start() {
    request("initialize", {{"capabilities", {{"textDocument", {{"codeAction", {{"disabledSupport", true}}}}}}}});
    notify("initialized", json::object());
  }
  json last = nullptr;  ///< the diagnostics last published on the document
  /// Checks the publications on `uri` since `from` against the document's `text` (the text
  /// they were checked on: checks run only here) and keeps the last.
  void published(const std::string& uri, const std::string& text, std::size_t from) {
    for (std::size_t i = from; i < sent.size(); ++i) {
      const json& m = sent[i];
      if (m.value("method", "") != "textDocument/publishDiagnostics" || m["params"]["uri"] != uri) continue;
      for (const json& d : m["params"]["diagnostics"]) {
        check_range(text, d.at("range"), "a diagnostic");
        for (const json& r : d.value("relatedInformation", json::array()))
          if (r["location"]["uri"] == uri) check_range(text, r["location"]["range"], "related information");
      }
      last = m["params"]["diagnostics"];
    }
  }
};

std::string uri_of(const std::string& path) { return "file://" + path; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const std::vector<Model>& all = models();
  const Model& base = all[in.ConsumeIntegralInRange<std::size_t>(0, all.size() - 1)];
  // Paths with only URI-safe characters, so that "file://" + path is the URI bodyls uses.
  if (base.path.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789/-._~") !=
      std::string::npos)
    return 0;
  const std::string uri = uri_of(base.path);
  std::string text = base.text;
  Session session;
  session.start();
  session.notify("textDocument/didOpen",
                 {{"textDocument", {{"uri", uri}, {"languageId", "body"}, {"version", 1}, {"text", text}}}});
  int version = 1;
  for (int step = 0; step < 40 && in.remaining_bytes() > 0; ++step) {
    const int op = in.ConsumeIntegralInRange<int>(0, 9);
    if (op <= 6) {  // an edit
      int line = 0, character = 0, end_line = 0, end_character = 0;
      if (in.ConsumeBool()) {  // at a UTF-8 byte offset (inside a character: its start)
        const std::size_t at = in.ConsumeIntegralInRange<std::size_t>(0, text.size());
        std::tie(line, character) = position_of(text, at);
        const std::size_t to = std::min(text.size(), at + in.ConsumeIntegralInRange<std::size_t>(0, 64));
        std::tie(end_line, end_character) = position_of(text, to);
      } else {  // at any UTF-16 position, also inside a surrogate pair or past the end
        line = in.ConsumeIntegralInRange<int>(0, static_cast<int>(lines_of(text).size()) + 1);
        character = in.ConsumeIntegralInRange<int>(0, 120);
        end_line = line + in.ConsumeIntegralInRange<int>(0, 2);
        end_character = in.ConsumeIntegralInRange<int>(0, 120);
      }
      std::string inserted;
      if (op <= 2) {
        inserted = valid_utf8(in.ConsumeRandomLengthString(16));
      } else if (op <= 4) {  // a paste of another model's text
        const std::string& other = all[in.ConsumeIntegralInRange<std::size_t>(0, all.size() - 1)].text;
        const std::size_t from = in.ConsumeIntegralInRange<std::size_t>(0, other.size());
        inserted = valid_utf8(other.substr(from, in.ConsumeIntegralInRange<std::size_t>(0, 400)));
      } else if (op == 5) {
        inserted = in.ConsumeBool() ? "\xF0\x9F\x98\x80" : "\xC3\xB6\r\n";  // a surrogate pair, a CR LF
      }                                                                     // op 6: a deletion
      std::size_t begin = offset_of(text, line, character), end = offset_of(text, end_line, end_character);
      if (end < begin) std::swap(begin, end);
      text.replace(begin, end - begin, inserted);
      ++version;
      session.notify(
          "textDocument/didChange",
          {{"textDocument", {{"uri", uri}, {"version", version}}},
           {"contentChanges", json::array({json{{"range",
                                                 {{"start", {{"line", line}, {"character", character}}},
                                                  {"end", {{"line", end_line}, {"character", end_character}}}}},
                                                {"text", inserted}}})}});
    } else if (op == 7) {  // a check now
      const std::size_t from = session.sent.size();
      session.server.run_pending_checks();
      session.published(uri, text, from);
    } else {  // requests at a random position
      const std::size_t at = in.ConsumeIntegralInRange<std::size_t>(0, text.size());
      const auto [line, character] = position_of(text, at);
      const json position = {{"line", line}, {"character", character}};
      const json doc = {{"uri", uri}};
      session.request("textDocument/hover", {{"textDocument", doc}, {"position", position}});
      session.request("textDocument/completion", {{"textDocument", doc}, {"position", position}});
      const json actions = session.request(
          "textDocument/codeAction",
          {{"textDocument", doc},
           {"range", {{"start", position}, {"end", position}}},
           {"context",
            {{"diagnostics", json::array()}, {"only", json::array({"quickfix", "quickfix.bodyfmt.upgrade"})}}}});
      for (const json& a : actions.value("result", json::array()))
        if (a.contains("edit"))
          for (const json& e : a["edit"]["changes"].value(uri, json::array())) check_range(text, e["range"], "an edit");
    }
  }
  const std::size_t from = session.sent.size();
  session.server.run_pending_checks();
  session.published(uri, text, from);
  // A fresh session on the final text publishes the same.
  Session fresh;
  fresh.start();
  fresh.notify("textDocument/didOpen",
               {{"textDocument", {{"uri", uri}, {"languageId", "body"}, {"version", 1}, {"text", text}}}});
  fresh.server.run_pending_checks();
  fresh.published(uri, text, 0);
  if (session.last != fresh.last) {
    std::fprintf(stderr, "after the edits:\n%s\na fresh check of the final text:\n%s\n", session.last.dump(1).c_str(),
                 fresh.last.dump(1).c_str());
    std::abort();
  }
  return 0;
}
