// GCC/Clang-style text output with source lines and carets, and the shared Report helpers.

#include <bodyfmt/report.h>

#include <bodyfmt/read_file.h>
#include "text/text_util.h"

#include <algorithm>
#include <charconv>
#include <limits>
#include <ostream>

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

void SourceLines::add(const std::string& file, std::string_view text) {
  std::optional<Text>& entry = files_[file];
  entry.emplace();
  entry->text = std::string(text);
  entry->lines = text::line_views(entry->text);
}

SourceLines SourceLines::any_file_for_columns() {
  SourceLines lines;
  lines.any_file_ = true;
  return lines;
}

void SourceLines::add_file(const std::string& file) { model_files_.insert(file); }

std::optional<std::string_view> SourceLines::line(const std::string& file, int line) {
  auto it = files_.find(file);
  if (it == files_.end()) {
    if (!any_file_ && model_files_.count(file) == 0) return std::nullopt;
    it = files_.emplace(file, std::nullopt).first;
    try {
      // The loader's own reader: only a regular file, read at its size (a large model's text
      // is held until its report is written). Any size: the loader has applied its limit.
      std::string why;
      if (std::optional<std::string> text =
              detail::read_regular_file(file, std::numeric_limits<std::uintmax_t>::max(), why)) {
        std::optional<Text>& entry = it->second;
        entry.emplace();
        entry->text = std::move(*text);
        entry->lines = text::line_views(entry->text);
      }
    } catch (...) {
      it->second.reset();
    }
  }
  const std::optional<Text>& entry = it->second;
  if (!entry || line < 1 || static_cast<std::size_t>(line) > entry->lines.size()) return std::nullopt;
  return entry->lines[static_cast<std::size_t>(line - 1)];
}

namespace {

void append_number(std::string& out, int value) {
  char buffer[16];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void append_location(std::string& out, const SourceLocation& location) {
  if (location.file.empty())
    out += "<input>";
  else
    out += location.file.str();
  if (location.line > 0) {
    out += ':';
    append_number(out, location.line);
    if (location.column > 0) {
      out += ':';
      append_number(out, location.column);
    }
  }
}

/// One character of a source line as printed: its bytes (or a stand-in), its columns on a
/// terminal, and where it starts in the line.
struct Glyph {
  std::size_t offset = 0;
  std::size_t size = 1;
  int width = 1;      ///< 0 for a tab, which the caret line copies
  bool shown = true;  ///< false: printed as '?' (control characters, invalid UTF-8)
};

/// East Asian wide and fullwidth characters take two terminal columns (UAX #11), so the
/// caret moves two columns for each.
bool is_wide(unsigned cp) {
  return (cp >= 0x1100 && cp <= 0x115F) || (cp >= 0x2E80 && cp <= 0x303E) || (cp >= 0x3041 && cp <= 0x33FF) ||
         (cp >= 0x3400 && cp <= 0x4DBF) || (cp >= 0x4E00 && cp <= 0x9FFF) || (cp >= 0xA000 && cp <= 0xA4CF) ||
         (cp >= 0xAC00 && cp <= 0xD7A3) || (cp >= 0xF900 && cp <= 0xFAFF) || (cp >= 0xFE30 && cp <= 0xFE4F) ||
         (cp >= 0xFF00 && cp <= 0xFF60) || (cp >= 0xFFE0 && cp <= 0xFFE6) || (cp >= 0x1F300 && cp <= 0x1F64F) ||
         (cp >= 0x1F900 && cp <= 0x1F9FF) || (cp >= 0x20000 && cp <= 0x3FFFD);
}

Glyph glyph_at(std::string_view line, std::size_t i) {
  Glyph g;
  g.offset = i;
  const unsigned char c = static_cast<unsigned char>(line[i]);
  if (c == '\t') {
    g.width = 0;
    return g;
  }
  if (c < 0x20 || c == 0x7F) {
    g.shown = false;
    return g;
  }
  if (c < 0x80) return g;
  std::size_t n = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
  unsigned cp = n == 2 ? (c & 0x1Fu) : n == 3 ? (c & 0x0Fu) : (c & 0x07u);
  for (std::size_t k = 1; k < n; ++k) {
    if (i + k >= line.size() || (static_cast<unsigned char>(line[i + k]) & 0xC0) != 0x80) n = 0;
    if (n == 0) break;
    cp = (cp << 6) | (static_cast<unsigned char>(line[i + k]) & 0x3Fu);
  }
  if (n == 0) {
    g.shown = false;
    return g;
  }
  g.size = n;
  g.width = is_wide(cp) ? 2 : 1;
  return g;
}

/// The source line as printed and the caret line under byte column `column`. A long line
/// (a flow list of thousands of numbers, or a binary file read as text) shows a window of
/// about kWindow bytes around the caret between "..." marks, so every diagnostic prints a
/// bounded excerpt; control bytes and invalid UTF-8 print as '?'. The caret line copies the
/// tabs and counts two columns for a wide character. Appended to `text` and `pad` (the
/// caret line without its caret).
constexpr std::size_t kWindow = 160;

void excerpt(std::string_view line, int column, std::string& text, std::string& pad) {
  const std::size_t caret = static_cast<std::size_t>(column > 0 ? column - 1 : 0);
  std::size_t begin = 0, end = line.size();
  if (line.size() > kWindow) {
    begin = caret > kWindow / 3 ? std::min(caret, line.size()) - kWindow / 3 : 0;
    end = std::min(line.size(), begin + kWindow);
  }
  if (begin > 0) {
    text += "...";
    pad += "   ";
  }
  std::size_t i = 0;
  // Start on a character boundary at or after `begin`.
  while (i < begin) i += glyph_at(line, i).size;
  for (; i < end;) {
    const unsigned char c = static_cast<unsigned char>(line[i]);
    if (c >= 0x20 && c < 0x7F) {  // the common case: printable ASCII, one column
      text += static_cast<char>(c);
      if (i < caret) pad += ' ';
      ++i;
      continue;
    }
    const Glyph g = glyph_at(line, i);
    if (i + g.size > end) break;
    if (g.shown)
      text.append(line.substr(i, g.size));
    else
      text += '?';
    if (i < caret) {
      if (g.width == 0)
        pad += '\t';
      else
        pad.append(static_cast<std::size_t>(g.width), ' ');
    }
    i += g.size;
  }
  if (i < line.size()) text += "...";
  // A column past the end (e.g. "missing key" at the end of the line) gets the caret there.
  for (std::size_t k = std::max(i, line.size()); k < caret; ++k) pad += ' ';
}

// GCC's colours: bold locations, bold red errors, bold magenta warnings, bold cyan notes,
// bold green carets.
std::string_view severity_code(Severity severity) {
  switch (severity) {
    case Severity::kNote: return "1;36";
    case Severity::kWarning: return "1;35";
    default: return "1;31";
  }
}

/// Appends `text` in the colour `code` (when colours are on).
class Painter {
 public:
  Painter(std::string& out, bool color) : out_(out), color_(color) {}
  void begin(std::string_view code) const {
    if (!color_) return;
    out_ += "\x1b[";
    out_ += code;
    out_ += 'm';
  }
  void end() const {
    if (color_) out_ += "\x1b[0m";
  }
  void location(const SourceLocation& location) const {
    begin("1");
    append_location(out_, location);
    out_ += ':';
    end();
  }
  void note() const {
    out_ += ' ';
    begin(severity_code(Severity::kNote));
    out_ += "note:";
    end();
    out_ += ' ';
  }

 private:
  std::string& out_;
  bool color_;
};

void append_text_diagnostic(std::string& out, const Diagnostic& d, SourceLines& sources, const TextOptions& options) {
  const Painter paint(out, options.color);
  paint.location(d.location);
  out += ' ';
  paint.begin(severity_code(d.severity));
  out += severity_name(d.severity);
  out += ':';
  paint.end();
  out += ' ';
  text::append_one_line(out, d.message);  // a name's line break would split the diagnostic
  if (!d.rule_id.empty()) {
    out += " [";
    out += d.rule_id;
    out += ']';
  }
  out += '\n';
  if (options.source_lines && d.location.known() && !d.location.file.empty()) {
    if (const std::optional<std::string_view> source = sources.line(d.location.file, d.location.line)) {
      std::string pad;
      excerpt(*source, d.location.column, out, pad);
      out += '\n';
      if (d.location.column > 0) {
        paint.begin("1;32");
        out += pad;
        out += '^';
        paint.end();
        out += '\n';
      }
    }
  }
  if (!options.notes) return;
  if (d.via) {
    paint.location(*d.via);
    paint.note();
    out += "reached through this alias\n";
  }
  if (!d.fix_hint.empty()) {
    paint.location(d.location);
    paint.note();
    text::append_one_line(out, d.fix_hint);
    out += '\n';
  }
  // Fix-its: the first few as edits, the rest counted (an upgrade can carry hundreds).
  constexpr std::size_t kShownFixes = 3;
  for (std::size_t i = 0; i < d.fixes.size() && i < kShownFixes; ++i) {
    const FixIt& f = d.fixes[i];
    paint.location(SourceLocation{f.file, f.line, f.column});
    paint.note();
    out += "fix-it (";
    out += fix_safety_name(f.safety);
    out += "): replace \"";
    text::append_one_line(out, f.original);
    out += "\" with \"";
    text::append_one_line(out, f.replacement);
    out += "\"\n";
  }
  if (d.fixes.size() > kShownFixes) {
    paint.location(d.location);
    paint.note();
    out += "... and ";
    out += std::to_string(d.fixes.size() - kShownFixes);
    out += " more fix-its\n";
  }
}

}  // namespace

std::string format_text_diagnostic(const Diagnostic& d, SourceLines& sources, const TextOptions& options) {
  std::string text;
  append_text_diagnostic(text, d, sources, options);
  return text;
}

std::string format_text_report(const Report& report, SourceLines& sources, const TextOptions& options) {
  std::string text;
  for (const Diagnostic& d : report.diagnostics) {
    if (d.severity == Severity::kNote && !options.notes) continue;
    append_text_diagnostic(text, d, sources, options);
  }
  return text;
}

void write_text_report(std::ostream& out, const Report& report, SourceLines& sources, const TextOptions& options) {
  constexpr std::size_t kBlock = 1 << 16;
  std::string text;
  text.reserve(2 * kBlock);
  for (const Diagnostic& d : report.diagnostics) {
    if (d.severity == Severity::kNote && !options.notes) continue;
    append_text_diagnostic(text, d, sources, options);
    if (text.size() >= kBlock) {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      text.clear();
    }
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
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
