// GCC/Clang-style text output with source lines and carets, and the shared Report helpers.

#include <bodyfmt/report.h>

#include "text/text_util.h"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace bodyfmt {

int Report::count(Severity severity) const {
  int n = 0;
  for (const Diagnostic& d : diagnostics) n += d.severity == severity;
  return n;
}

std::map<std::string, int> Report::counts_by_rule() const {
  std::map<std::string, int> counts;
  for (const Diagnostic& d : diagnostics) ++counts[d.rule_id];
  return counts;
}

void SourceLines::add(const std::string& file, std::string_view text) { files_[file] = text::split_lines(text); }

const std::string* SourceLines::line(const std::string& file, int line) {
  auto it = files_.find(file);
  if (it == files_.end()) {
    std::optional<std::vector<std::string>> lines;
    try {
      std::ifstream in(file, std::ios::binary);
      if (in.is_open()) {
        std::ostringstream text;
        text << in.rdbuf();
        lines = text::split_lines(text.str());
      }
    } catch (...) {
      lines.reset();
    }
    it = files_.emplace(file, std::move(lines)).first;
  }
  if (!it->second || line < 1 || static_cast<std::size_t>(line) > it->second->size()) return nullptr;
  return &(*it->second)[static_cast<std::size_t>(line - 1)];
}

namespace {

std::string location_text(const SourceLocation& location) {
  std::string text = location.file.empty() ? std::string("<input>") : location.file;
  if (location.line > 0) {
    text += ':' + std::to_string(location.line);
    if (location.column > 0) text += ':' + std::to_string(location.column);
  }
  return text;
}

/// Spaces (and the source's own tabs) up to byte column `column`, one per UTF-8 character.
std::string caret_line(const std::string& source, int column) {
  std::string pad;
  const std::size_t limit = std::min(source.size(), static_cast<std::size_t>(column > 0 ? column - 1 : 0));
  for (std::size_t i = 0; i < limit; ++i) {
    const unsigned char c = static_cast<unsigned char>(source[i]);
    if (c == '\t')
      pad += '\t';
    else if ((c & 0xC0) != 0x80)
      pad += ' ';  // skip UTF-8 continuation bytes
  }
  // A column past the end (e.g. "missing key" at the end of the line) gets the caret there.
  for (std::size_t i = limit; i + 1 < static_cast<std::size_t>(column > 0 ? column : 1); ++i) pad += ' ';
  return pad + '^';
}

}  // namespace

std::string format_text_diagnostic(const Diagnostic& d, SourceLines& sources, const TextOptions& options) {
  // GCC's colours: bold locations, bold red errors, bold magenta warnings, bold cyan notes,
  // bold green carets.
  const auto paint = [&](std::string_view code, const std::string& text) {
    return options.color ? "\x1b[" + std::string(code) + "m" + text + "\x1b[0m" : text;
  };
  const auto severity_code = [](Severity severity) -> std::string_view {
    switch (severity) {
      case Severity::kNote: return "1;36";
      case Severity::kWarning: return "1;35";
      default: return "1;31";
    }
  };
  std::string text = paint("1", location_text(d.location) + ":") + " " +
                     paint(severity_code(d.severity), std::string(severity_name(d.severity)) + ":") + " " + d.message;
  if (!d.rule_id.empty()) text += " [" + d.rule_id + "]";
  text += '\n';
  if (options.source_lines && d.location.known() && !d.location.file.empty()) {
    if (const std::string* source = sources.line(d.location.file, d.location.line)) {
      text += *source + '\n';
      if (d.location.column > 0) text += paint("1;32", caret_line(*source, d.location.column)) + '\n';
    }
  }
  const std::string note = paint(severity_code(Severity::kNote), "note:");
  if (d.via) text += paint("1", location_text(*d.via) + ":") + " " + note + " reached through this alias\n";
  if (!d.fix_hint.empty()) text += paint("1", location_text(d.location) + ":") + " " + note + " " + d.fix_hint + '\n';
  return text;
}

std::string format_text_report(const Report& report, SourceLines& sources, const TextOptions& options) {
  std::string text;
  for (const Diagnostic& d : report.diagnostics) {
    if (d.severity == Severity::kNote && !options.notes) continue;
    text += format_text_diagnostic(d, sources, options);
  }
  return text;
}

std::string format_summary_line(const Report& report) {
  auto plural = [](int n, const char* word) { return std::to_string(n) + ' ' + word + (n == 1 ? "" : "s"); };
  const int errors = report.count(Severity::kError) + report.count(Severity::kFatal);
  std::string text =
      "bodycheck: " + plural(static_cast<int>(report.files.size()), "file") + " checked: " + plural(errors, "error") +
      ", " + plural(report.count(Severity::kWarning), "warning") + ", " + plural(report.count(Severity::kNote), "note");
  if (report.suppressed > 0) text += ", " + std::to_string(report.suppressed) + " suppressed";
  if (report.disabled > 0) text += ", " + std::to_string(report.disabled) + " disabled";
  return text + '\n';
}

}  // namespace bodyfmt
