// JSON output (docs/bodycheck-json.md) and the JSON string escaper shared with SARIF.
// No JSON library is a dependency, so the documents are written by hand; every string goes
// through json_quote.

#include <bodyfmt/report.h>

namespace bodyfmt {

namespace {

/// Length of the valid UTF-8 sequence starting at s[i], or 0 when it is not valid.
std::size_t utf8_sequence(std::string_view s, std::size_t i) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  std::size_t n = 0;
  unsigned min = 0;
  unsigned value = 0;
  if (c < 0x80) return 1;
  if ((c & 0xE0) == 0xC0) n = 2, min = 0x80, value = c & 0x1F;
  else if ((c & 0xF0) == 0xE0) n = 3, min = 0x800, value = c & 0x0F;
  else if ((c & 0xF8) == 0xF0) n = 4, min = 0x10000, value = c & 0x07;
  else return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const unsigned char cc = static_cast<unsigned char>(s[i + k]);
    if ((cc & 0xC0) != 0x80) return 0;
    value = (value << 6) | (cc & 0x3F);
  }
  if (value < min || value > 0x10FFFF || (value >= 0xD800 && value <= 0xDFFF)) return 0;
  return n;
}

}  // namespace

std::string json_quote(std::string_view s) {
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(s.size() + 2);
  out += '"';
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char ch = s[i];
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c >= 0x80) {
      const std::size_t n = utf8_sequence(s, i);
      if (n == 0) {
        out += "\\ufffd";  // invalid UTF-8 byte: the replacement character
      } else {
        out.append(s.substr(i, n));
        i += n - 1;
      }
      continue;
    }
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          out += "\\u00";
          out += kHex[c >> 4];
          out += kHex[c & 0xF];
        } else {
          out += ch;
        }
    }
  }
  out += '"';
  return out;
}

namespace {

std::string_view json_severity(Severity s) {
  switch (s) {
    case Severity::kNote: return "note";
    case Severity::kWarning: return "warning";
    case Severity::kError: return "error";
    case Severity::kFatal: return "fatal";
  }
  return "error";
}

std::string location_json(const SourceLocation& loc) {
  return "{\"file\": " + json_quote(loc.file) + ", \"line\": " + std::to_string(loc.line) +
         ", \"column\": " + std::to_string(loc.column) + "}";
}

}  // namespace

std::string format_json_report(const Report& report, const ToolInfo& tool) {
  std::string out = "{\n";
  out += "  \"version\": 1,\n";
  out += "  \"tool\": {\"name\": " + json_quote(tool.name) + ", \"version\": " + json_quote(tool.version) + "},\n";
  out += "  \"files\": [";
  for (std::size_t i = 0; i < report.files.size(); ++i) {
    out += i == 0 ? "\n    " : ",\n    ";
    out += json_quote(report.files[i]);
  }
  out += report.files.empty() ? "],\n" : "\n  ],\n";
  out += "  \"diagnostics\": [";
  for (std::size_t i = 0; i < report.diagnostics.size(); ++i) {
    const Diagnostic& d = report.diagnostics[i];
    out += i == 0 ? "\n    {" : ",\n    {";
    out += "\"file\": " + json_quote(d.location.file);
    out += ", \"line\": " + std::to_string(d.location.line);
    out += ", \"column\": " + std::to_string(d.location.column);
    out += ", \"severity\": " + json_quote(json_severity(d.severity));
    out += ", \"rule\": " + json_quote(d.rule_id);
    out += ", \"message\": " + json_quote(d.message);
    out += ", \"via\": " + (d.via ? location_json(*d.via) : std::string("null"));
    out += ", \"fix_hint\": " + (d.fix_hint.empty() ? std::string("null") : json_quote(d.fix_hint));
    out += "}";
  }
  out += report.diagnostics.empty() ? "],\n" : "\n  ],\n";
  out += "  \"summary\": {";
  out += "\"files\": " + std::to_string(report.files.size());
  out += ", \"fatal\": " + std::to_string(report.count(Severity::kFatal));
  out += ", \"errors\": " + std::to_string(report.count(Severity::kError));
  out += ", \"warnings\": " + std::to_string(report.count(Severity::kWarning));
  out += ", \"notes\": " + std::to_string(report.count(Severity::kNote));
  out += ", \"suppressed\": " + std::to_string(report.suppressed);
  out += ", \"disabled\": " + std::to_string(report.disabled);
  out += ", \"by_rule\": {";
  bool first = true;
  for (const auto& [rule, n] : report.counts_by_rule()) {
    out += first ? "" : ", ";
    first = false;
    out += json_quote(rule) + ": " + std::to_string(n);
  }
  out += "}}\n}\n";
  return out;
}

}  // namespace bodyfmt
