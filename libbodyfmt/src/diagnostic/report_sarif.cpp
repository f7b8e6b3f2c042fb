// SARIF 2.1.0 output (OASIS SARIF v2.1.0), accepted by GitHub code scanning and checked in
// the test suite by Microsoft's SARIF Multitool `validate` (no errors, no warnings).
//
// Multitool rules that shape this writer: SARIF2001 (messages end with a period), SARIF2005
// (tool.driver has version and informationUri), SARIF1004/SARIF1005 (uriBaseId declared
// with an absolute, slash-terminated URI), SARIF1009 (indices in range).

#include <bodyfmt/report.h>

#include "text/text_util.h"

using bodyfmt::text::json_quote;
#include <bodyfmt/rules.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <system_error>

namespace bodyfmt {
namespace {

constexpr std::string_view kSrcRoot = "%SRCROOT%";

std::string_view sarif_level(Severity s) {
  switch (s) {
    case Severity::kNote: return "note";
    case Severity::kWarning: return "warning";
    case Severity::kError:
    case Severity::kFatal: return "error";
  }
  return "error";
}

/// Text for a SARIF message: trimmed, capitalised, ending with a period (SARIF2001).
std::string sentence(std::string text) {
  while (!text.empty() && (text.back() == ' ' || text.back() == '\n')) text.pop_back();
  if (text.empty()) return ".";
  if (text.front() >= 'a' && text.front() <= 'z') text.front() = static_cast<char>(text.front() - 'a' + 'A');
  if (text.back() != '.') text += '.';
  return text;
}

/// `structure-no-parent` -> `StructureNoParent`, the rule's friendly name (SARIF2012).
std::string pascal_case(std::string_view id) {
  std::string out;
  bool upper = true;
  for (char c : id) {
    if (c == '-' || c == '_' || c == '.') {
      upper = true;
      continue;
    }
    out += upper && c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
    upper = false;
  }
  return out;
}

struct ArtifactUri {
  std::string uri;
  bool relative = false;  // relative to %SRCROOT%
};

class UriMaker {
 public:
  explicit UriMaker(const std::string& base_dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path base = base_dir.empty() ? fs::current_path(ec) : fs::absolute(base_dir, ec);
    base_ = base.lexically_normal();
    std::string generic = base_.generic_string();
    if (generic.empty() || generic.back() != '/') generic += '/';
    base_uri_ = "file://" + text::uri_path_encode(generic);
  }

  const std::string& base_uri() const { return base_uri_; }

  ArtifactUri make(const std::string& file) const {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path abs = fs::absolute(fs::path(file), ec).lexically_normal();
    fs::path rel = abs.lexically_relative(base_);
    const std::string rel_text = rel.generic_string();
    if (!rel.empty() && rel_text != "." && rel_text.rfind("..", 0) != 0) return {text::uri_path_encode(rel_text), true};
    return {"file://" + text::uri_path_encode(abs.generic_string()), false};
  }

 private:
  std::filesystem::path base_;
  std::string base_uri_;
};

/// SARIF columns count characters (columnKind unicodeCodePoints); ours count bytes.
int code_point_column(SourceLines& sources, const SourceLocation& loc) {
  const std::optional<std::string_view> line = sources.line(loc.file, loc.line);
  if (!line) return loc.column;
  int column = 1;
  const std::size_t limit = std::min(line->size(), static_cast<std::size_t>(loc.column - 1));
  for (std::size_t i = 0; i < limit; ++i)
    if ((static_cast<unsigned char>((*line)[i]) & 0xC0) != 0x80) ++column;
  return column + (loc.column - 1 - static_cast<int>(limit));
}

std::string physical_location(const SourceLocation& loc, const UriMaker& uris, SourceLines& sources,
                              const std::map<std::string, std::size_t>& artifact_index) {
  const ArtifactUri uri = uris.make(loc.file);
  std::string out = "{\"artifactLocation\": {\"uri\": " + json_quote(uri.uri);
  if (uri.relative) out += ", \"uriBaseId\": " + json_quote(kSrcRoot);
  auto index = artifact_index.find(loc.file);
  if (index != artifact_index.end()) out += ", \"index\": " + std::to_string(index->second);
  out += "}";
  if (loc.line > 0) {
    out += ", \"region\": {\"startLine\": " + std::to_string(loc.line);
    if (loc.column > 0) out += ", \"startColumn\": " + std::to_string(code_point_column(sources, loc));
    out += "}";
  }
  return out + "}";
}

/// One SARIF fix holding every edit of the diagnostic, grouped per file (artifactChanges),
/// each a byte range (deletedRegion byteOffset/byteLength) and its new text.
std::string sarif_fix(const std::vector<FixIt>& fixes, const UriMaker& uris) {
  std::map<std::string, std::vector<const FixIt*>> by_file;
  for (const FixIt& f : fixes) by_file[f.file.str()].push_back(&f);
  std::string description = "Apply " + std::to_string(fixes.size()) + " edit" + (fixes.size() == 1 ? "" : "s") + " (" +
                            std::string(fix_safety_name(fixes.front().safety)) + ": ";
  switch (fixes.front().safety) {
    case FixSafety::kSafe: description += "bodycheck --fix applies it)."; break;
    case FixSafety::kUpgrade: description += "bodycheck --fix --upgrade applies it)."; break;
    case FixSafety::kUnsafe: description += "it changes the loaded model; never applied automatically)."; break;
  }
  std::string out = "{\"description\": {\"text\": " + json_quote(description) + "}, \"artifactChanges\": [";
  bool first_file = true;
  for (const auto& [file, edits] : by_file) {
    const ArtifactUri uri = uris.make(file);
    out += first_file ? "" : ", ";
    first_file = false;
    out += "{\"artifactLocation\": {\"uri\": " + json_quote(uri.uri);
    if (uri.relative) out += ", \"uriBaseId\": " + json_quote(kSrcRoot);
    out += "}, \"replacements\": [";
    for (std::size_t i = 0; i < edits.size(); ++i) {
      out += i == 0 ? "" : ", ";
      out += "{\"deletedRegion\": {\"byteOffset\": " + std::to_string(edits[i]->begin) +
             ", \"byteLength\": " + std::to_string(edits[i]->end - edits[i]->begin) +
             "}, \"insertedContent\": {\"text\": " + json_quote(edits[i]->replacement) + "}}";
    }
    out += "]}";
  }
  return out + "]}";
}

}  // namespace

std::string format_sarif_report(const Report& report, const ToolInfo& tool, const std::string& base_dir) {
  const UriMaker uris(base_dir);
  SourceLines sources = SourceLines::any_file_for_columns();  // counts characters, quotes nothing
  const auto& rules = all_rules();

  std::string out = "{\n";
  out += "  \"$schema\": \"https://json.schemastore.org/sarif-2.1.0.json\",\n";
  out += "  \"version\": \"2.1.0\",\n";
  out += "  \"runs\": [\n    {\n";

  // tool.driver with the whole rule table: ruleIndex is the row number.
  out += "      \"tool\": {\n        \"driver\": {\n";
  out += "          \"name\": " + json_quote(tool.name) + ",\n";
  out += "          \"version\": " + json_quote(tool.version.empty() ? "0" : tool.version) + ",\n";
  if (!tool.information_uri.empty()) out += "          \"informationUri\": " + json_quote(tool.information_uri) + ",\n";
  out += "          \"rules\": [";
  for (std::size_t i = 0; i < rules.size(); ++i) {
    const RuleInfo& r = rules[i];
    std::string full = sentence(std::string(r.summary)) + ' ' + sentence(std::string(r.rationale));
    if (!r.tolerance.empty()) full += " Tolerance: " + sentence(std::string(r.tolerance));
    out += i == 0 ? "\n" : ",\n";
    out += "            {\"id\": " + json_quote(r.id) + ", \"name\": " + json_quote(pascal_case(r.id)) +
           ", \"shortDescription\": {\"text\": " + json_quote(sentence(std::string(r.summary))) +
           "}, \"fullDescription\": {\"text\": " + json_quote(full) +
           "}, \"defaultConfiguration\": {\"level\": " + json_quote(sarif_level(r.default_severity)) + "}}";
  }
  out += rules.empty() ? "]\n" : "\n          ]\n";
  out += "        }\n      },\n";

  out +=
      "      \"originalUriBaseIds\": {" + json_quote(kSrcRoot) + ": {\"uri\": " + json_quote(uris.base_uri()) + "}},\n";
  out += "      \"columnKind\": \"unicodeCodePoints\",\n";

  // Every checked file is an artifact, so that files without results are listed too.
  std::map<std::string, std::size_t> artifact_index;
  out += "      \"artifacts\": [";
  for (std::size_t i = 0; i < report.files.size(); ++i) {
    const std::string& file = report.files[i];
    if (artifact_index.count(file)) continue;
    const ArtifactUri uri = uris.make(file);
    out += artifact_index.empty() ? "\n" : ",\n";
    out += "        {\"location\": {\"uri\": " + json_quote(uri.uri);
    if (uri.relative) out += ", \"uriBaseId\": " + json_quote(kSrcRoot);
    out += "}, \"roles\": [\"analysisTarget\"]}";
    const std::size_t index = artifact_index.size();
    artifact_index.emplace(file, index);
  }
  out += artifact_index.empty() ? "],\n" : "\n      ],\n";

  out += "      \"results\": [";
  for (std::size_t i = 0; i < report.diagnostics.size(); ++i) {
    const Diagnostic& d = report.diagnostics[i];
    std::string text = sentence(d.message);
    if (!d.fix_hint.empty()) text += " Fix: " + sentence(d.fix_hint);
    out += i == 0 ? "\n" : ",\n";
    out += "        {\"ruleId\": " + json_quote(d.rule_id.empty() ? std::string("unknown") : d.rule_id);
    const auto row = std::lower_bound(rules.begin(), rules.end(), d.rule_id,
                                      [](const RuleInfo& r, const std::string& key) { return r.id < key; });
    if (row != rules.end() && row->id == d.rule_id) out += ", \"ruleIndex\": " + std::to_string(row - rules.begin());
    out += ", \"level\": " + json_quote(sarif_level(d.severity));
    out += ", \"message\": {\"text\": " + json_quote(text) + "}";
    if (!d.location.file.empty())
      out +=
          ", \"locations\": [{\"physicalLocation\": " + physical_location(d.location, uris, sources, artifact_index) +
          "}]";
    if (!d.fixes.empty()) out += ", \"fixes\": [" + sarif_fix(d.fixes, uris) + "]";
    if (d.via && !d.via->file.empty())
      out += ", \"relatedLocations\": [{\"id\": 1, \"physicalLocation\": " +
             physical_location(*d.via, uris, sources, artifact_index) +
             ", \"message\": {\"text\": \"Reached through this alias.\"}}]";
    out += "}";
  }
  out += report.diagnostics.empty() ? "]\n" : "\n      ]\n";
  out += "    }\n  ]\n}\n";
  return out;
}

}  // namespace bodyfmt
