#include "lsp_convert.h"

#include "uri.h"

#include <bodyfmt/read_file.h>

#include <filesystem>

namespace bodyfmt::lsp {

using json = nlohmann::json;

namespace {

int to_int(const json& value) {
  if (!value.is_number()) throw json::type_error::create(302, "a position's line and character are numbers", &value);
  const double v = value.get<double>();
  if (!(v >= 0)) return 0;
  return v > 2e9 ? 2000000000 : static_cast<int>(v);
}

std::string canonical(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path made = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : made.string();
}

int lsp_severity(Severity severity) {
  switch (severity) {
    case Severity::kFatal:
    case Severity::kError: return 1;
    case Severity::kWarning: return 2;
    case Severity::kNote: return 3;
  }
  return 1;
}

}  // namespace

Utf16Position position_from_json(const json& position) {
  return {to_int(position.at("line")), to_int(position.at("character"))};
}

Utf16Range range_from_json(const json& range) {
  return {position_from_json(range.at("start")), position_from_json(range.at("end"))};
}

json to_json(Utf16Position position) { return json{{"line", position.line}, {"character", position.character}}; }

json to_json(Utf16Range range) { return json{{"start", to_json(range.start)}, {"end", to_json(range.end)}}; }

FileTexts::FileTexts(std::string document_path, std::string document_uri, const std::string& document_text,
                     const std::map<std::string, std::string>& other_texts)
    : document_path_(std::move(document_path)),
      document_uri_(std::move(document_uri)),
      document_text_(document_text),
      other_texts_(other_texts) {}

const std::string* FileTexts::text(const std::string& file) {
  if (file.empty() || file == document_path_) return &document_text_;
  auto known = read_.find(file);
  if (known != read_.end()) return known->second.get();
  const std::string key = canonical(file);
  std::unique_ptr<std::string> text;
  if (key == canonical(document_path_)) return &document_text_;
  auto open = other_texts_.find(key);
  if (open != other_texts_.end()) {
    text = std::make_unique<std::string>(open->second);
  } else {
    std::string why;
    if (auto read = read_regular_file(file, std::uintmax_t{256} << 20, why))
      text = std::make_unique<std::string>(*read);
  }
  return read_.emplace(file, std::move(text)).first->second.get();
}

const TextLines* FileTexts::lines(const std::string& file) {
  auto known = lines_.find(file);
  if (known != lines_.end()) return known->second.get();
  const std::string* t = text(file);
  return lines_.emplace(file, t ? std::make_unique<TextLines>(*t) : nullptr).first->second.get();
}

std::string FileTexts::uri(const std::string& file) const {
  if (file.empty() || file == document_path_) return document_uri_;
  if (canonical(file) == canonical(document_path_)) return document_uri_;
  return uri_from_path(file);
}

Utf16Range FileTexts::token_range(const std::string& file, int line, int column) {
  if (line <= 0) return {};
  if (const TextLines* l = lines(file)) return l->token_range(line, column);
  // Unreadable: the byte column stands for the character.
  const Utf16Position at{line - 1, std::max(column - 1, 0)};
  return {at, at};
}

std::optional<Utf16Range> FileTexts::byte_range(const std::string& file, std::size_t begin, std::size_t end) {
  const std::string* t = text(file);
  const TextLines* l = lines(file);
  if (!t || !l || begin > end || end > t->size()) return std::nullopt;
  return Utf16Range{l->position_of(begin), l->position_of(end)};
}

json diagnostic_to_json(const Diagnostic& d, FileTexts& texts) {
  const std::string file = d.location.file.str();
  const Utf16Range range = texts.token_range(file, d.location.line, d.location.column);
  json out = {{"range", to_json(range)},
              {"severity", lsp_severity(d.severity)},
              {"code", d.rule_id},
              {"source", "bodyfmt"},
              {"message", d.message}};
  json related = json::array();
  if (d.via && d.via->known()) {
    const std::string via_file = d.via->file.empty() ? file : d.via->file.str();
    related.push_back(
        {{"location",
          {{"uri", texts.uri(via_file)}, {"range", to_json(texts.token_range(via_file, d.via->line, d.via->column))}}},
         {"message", "reached through this alias"}});
  }
  if (!d.fix_hint.empty())
    related.push_back({{"location", {{"uri", texts.uri(file)}, {"range", to_json(range)}}}, {"message", d.fix_hint}});
  if (!related.empty()) out["relatedInformation"] = std::move(related);
  return out;
}

}  // namespace bodyfmt::lsp
