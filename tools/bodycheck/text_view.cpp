#include "text_view.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <tuple>
#include <utility>

namespace bodyfmt::tools {
namespace {

/// 0 for errors (and fatal errors), 1 for warnings, 2 for notes: the order they are printed in.
int band(Severity severity) {
  switch (severity) {
    case Severity::kNote: return 2;
    case Severity::kWarning: return 1;
    default: return 0;
  }
}

bool has_safe_fix(const Diagnostic& d) {
  return std::any_of(d.fixes.begin(), d.fixes.end(), [](const FixIt& f) { return f.safety == FixSafety::kSafe; });
}

std::string plural(std::size_t n, const char* word) { return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s"); }

/// "at lines 13, 14, 20, ..." wrapped under the note at 100 columns; `width` is the length of the
/// line before it.
std::string folded_lines(const std::vector<const Diagnostic*>& rest, std::size_t width) {
  std::string text = "at line" + std::string(rest.size() == 1 ? " " : "s ");
  width += text.size();
  for (std::size_t i = 0; i < rest.size(); ++i) {
    std::string item = std::to_string(rest[i]->location.line);
    if (i + 1 < rest.size()) item += ',';
    if (width + item.size() + 1 > 100) {
      text += "\n   ";
      width = 3;
    } else if (i > 0) {
      text += ' ';
      ++width;
    }
    text += item;
    width += item.size();
  }
  return text;
}

/// `word` as one shell word: as it is when it holds only characters no shell treats specially.
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.' || c == '/' || c == '+' || c == '=' || c == ':' || c == ',';
  });
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

void write_text_view(std::ostream& out, const Report& report, SourceLines& sources, const TextView& view) {
  // What is printed, by band, keeping the report's file and line order within a band.
  std::vector<const Diagnostic*> shown;
  std::size_t hidden = 0, fixable = 0;
  for (const Diagnostic& d : report.diagnostics) {
    if (has_safe_fix(d)) ++fixable;
    if (d.severity == Severity::kNote && !view.text.notes) continue;
    if (d.severity < view.min_severity) {
      ++hidden;
      continue;
    }
    shown.push_back(&d);
  }
  std::stable_sort(shown.begin(), shown.end(),
                   [](const Diagnostic* a, const Diagnostic* b) { return band(a->severity) < band(b->severity); });

  // The findings of each (band, file, rule) that fold, in order.
  std::map<std::tuple<int, std::string, std::string>, std::vector<const Diagnostic*>> groups;
  for (const Diagnostic* d : shown)
    if (band(d->severity) > 0) groups[{band(d->severity), d->location.file.str(), d->rule_id}].push_back(d);

  std::string text;
  for (const Diagnostic* d : shown) {
    std::vector<const Diagnostic*>* group = nullptr;
    if (band(d->severity) > 0) {
      auto it = groups.find({band(d->severity), d->location.file.str(), d->rule_id});
      if (it->second.size() >= static_cast<std::size_t>(kFoldAt)) group = &it->second;
    }
    if (group && group->front() != d) continue;  // printed with the first of its block
    text += format_text_diagnostic(*d, sources, view.text);
    if (group) {
      const std::vector<const Diagnostic*> rest(group->begin() + 1, group->end());
      const std::string file = d->location.file.empty() ? std::string("<input>") : d->location.file.str();
      const std::string head = fmt::format("{}: note: {} more [{}] in this file, ", file, rest.size(), d->rule_id);
      text += head + folded_lines(rest, head.size()) + '\n';
    }
    if (text.size() >= (1u << 16)) {
      out << text;
      text.clear();
    }
  }
  out << text;
  if (!view.summary) return;
  out << format_summary_line(report);
  if (hidden > 0)
    out << fmt::format("bodycheck: {} below {} not shown (--min-severity)\n", plural(hidden, "finding"),
                       severity_name(view.min_severity));
  const int errors = report.count(Severity::kError) + report.count(Severity::kFatal);
  if (hidden == 0 && errors > 0 && report.count(Severity::kWarning) > 0)
    out << "bodycheck: --min-severity error prints the errors only\n";
  if (fixable > 0) {
    std::string command = "bodycheck --fix";
    for (const std::string& path : view.paths) command += ' ' + shell_word(path);
    out << fmt::format("bodycheck: {} {} a safe fix-it: `{}` applies {} (add --dry-run to see the diff first)\n",
                       plural(fixable, "finding"), fixable == 1 ? "has" : "have", command,
                       fixable == 1 ? "it" : "them");
  }
}

}  // namespace bodyfmt::tools
