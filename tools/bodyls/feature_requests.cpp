#include "feature_requests.h"

#include "language_features.h"
#include "lsp_convert.h"

namespace bodyfmt::lsp {

using json = nlohmann::json;

namespace {

const char* const kMethods[] = {"textDocument/hover",         "textDocument/completion",    "textDocument/definition",
                                "textDocument/references",    "textDocument/prepareRename", "textDocument/rename",
                                "textDocument/documentSymbol"};

json range_json(FileTexts& texts, const std::string& file, const TextRange& range) {
  if (const TextLines* lines = texts.lines(file)) return to_json(utf16_range_of(*lines, range));
  // Unreadable: the byte columns stand for the characters.
  return to_json(
      Utf16Range{{range.begin.line - 1, range.begin.column - 1}, {range.end.line - 1, range.end.column - 1}});
}

int completion_kind(CompletionKind kind) {
  switch (kind) {
    case CompletionKind::kKey: return 10;       // Property
    case CompletionKind::kValue: return 12;     // Value
    case CompletionKind::kLinkName: return 18;  // Reference
    case CompletionKind::kAnchor: return 18;
    case CompletionKind::kFile: return 17;  // File
  }
  return 1;
}

int symbol_kind(SymbolKind kind) {
  switch (kind) {
    case SymbolKind::kBody: return 2;     // Module
    case SymbolKind::kLink: return 5;     // Class
    case SymbolKind::kDevice: return 8;   // Field
    case SymbolKind::kElement: return 7;  // Property
  }
  return 5;
}

json symbol_json(FileTexts& texts, const std::string& path, const Symbol& s) {
  json out = {{"name", s.name.empty() ? std::string("(unnamed)") : s.name},
              {"kind", symbol_kind(s.kind)},
              {"range", range_json(texts, path, s.range)},
              {"selectionRange", range_json(texts, path, s.selection)}};
  if (!s.detail.empty()) out["detail"] = s.detail;
  json children = json::array();
  for (const Symbol& c : s.children) children.push_back(symbol_json(texts, path, c));
  if (!children.empty()) out["children"] = std::move(children);
  return out;
}

json edits_json(FileTexts& texts, const std::vector<TextEdit>& edits) {
  json changes = json::object();
  for (const TextEdit& e : edits) {
    const std::string uri = texts.uri(e.where.file);
    if (!changes.contains(uri)) changes[uri] = json::array();
    changes[uri].push_back({{"range", range_json(texts, e.where.file, e.where.range)}, {"newText", e.new_text}});
  }
  return json{{"changes", changes}};
}

}  // namespace

TextPoint text_point_of(const TextLines& lines, Utf16Position position) {
  const int last = std::max(lines.line_count() - 1, 0);
  if (position.line > last) return {last + 1, static_cast<int>(lines.line(last).size()) + 1};
  const int line = std::max(position.line, 0);
  return {line + 1, static_cast<int>(lines.offset_of({line, position.character}) - lines.line_start(line)) + 1};
}

Utf16Range utf16_range_of(const TextLines& lines, const TextRange& range) {
  return {lines.position_of(lines.offset_of_column(range.begin.line, range.begin.column)),
          lines.position_of(lines.offset_of_column(range.end.line, range.end.column))};
}

bool prefers_plain_text(const json& capabilities, const char* feature) {
  const json* formats = &capabilities;
  for (const char* key : {"textDocument", feature, "contentFormat"}) {
    if (!formats->is_object() || !formats->contains(key)) return false;
    formats = &(*formats)[key];
  }
  if (!formats->is_array()) return false;
  for (const json& kind : *formats) {
    if (kind == "markdown") return false;
    if (kind == "plaintext") return true;
  }
  return false;  // neither: the protocol's other kinds are none bodyls writes
}

bool is_feature_method(const std::string& method) {
  return std::find(std::begin(kMethods), std::end(kMethods), method) != std::end(kMethods);
}

std::optional<json> answer_feature(const std::string& method, const json& params, const FeatureDocument& document) {
  if (!is_feature_method(method)) return std::nullopt;
  static const std::map<std::string, std::string> no_other_texts;
  FileTexts texts(document.path, document.uri, document.text,
                  document.model_texts ? *document.model_texts : no_other_texts);
  const TextLines lines(document.text);
  Document doc;
  doc.path = document.path;
  doc.text = document.text;
  doc.model = document.model.get();
  doc.model_is_current = document.model_is_current;
  if (method == "textDocument/documentSymbol") {
    json out = json::array();
    for (const Symbol& s : document_symbols(doc)) out.push_back(symbol_json(texts, document.path, s));
    return out;
  }
  const TextPoint at = text_point_of(lines, position_from_json(params.at("position")));
  if (method == "textDocument/hover") {
    const std::optional<Hover> h = hover(doc, at);
    if (!h) return json(nullptr);
    const json contents = document.plain_text ? json{{"kind", "plaintext"}, {"value", h->plain_text}}
                                              : json{{"kind", "markdown"}, {"value", h->markdown}};
    return json{{"contents", contents}, {"range", range_json(texts, document.path, h->range)}};
  }
  if (method == "textDocument/completion") {
    json items = json::array();
    for (const CompletionItem& c : complete(doc, at)) {
      json item = {{"label", c.label}, {"kind", completion_kind(c.kind)}};
      if (!c.detail.empty()) item["detail"] = c.detail;
      item["textEdit"] = {{"range", range_json(texts, document.path, c.replace)},
                          {"newText", c.insert_text.empty() ? c.label : c.insert_text}};
      items.push_back(std::move(item));
    }
    return json{{"isIncomplete", false}, {"items", items}};
  }
  if (method == "textDocument/definition" || method == "textDocument/references") {
    const std::vector<FileRange> found =
        method == "textDocument/definition"
            ? definition(doc, at)
            : references(doc, at, params.value("context", json::object()).value("includeDeclaration", false));
    json out = json::array();
    for (const FileRange& r : found) {
      if (!r.to_token_end) {
        out.push_back({{"uri", texts.uri(r.file)}, {"range", range_json(texts, r.file, r.range)}});
        continue;
      }
      // A place the model read: its token in that file's text; a file that cannot be read now
      // is no place to go.
      const TextLines* file_lines = texts.lines(r.file);
      if (!file_lines || r.range.begin.line > file_lines->line_count()) continue;
      out.push_back({{"uri", texts.uri(r.file)},
                     {"range", to_json(file_lines->token_range(r.range.begin.line, r.range.begin.column))}});
    }
    if (out.empty() && method == "textDocument/definition") return json(nullptr);
    return out;
  }
  std::string why;
  if (method == "textDocument/prepareRename") {
    const std::optional<TextRange> range = prepare_rename(doc, at, why);
    if (!range) return json(nullptr);
    return range_json(texts, document.path, *range);
  }
  // textDocument/rename
  const std::string new_name = params.at("newName").get<std::string>();
  const std::optional<std::vector<TextEdit>> edits = rename_link(doc, at, new_name, why);
  if (!edits) throw std::invalid_argument("cannot rename: " + why);
  return edits_json(texts, *edits);
}

}  // namespace bodyfmt::lsp
