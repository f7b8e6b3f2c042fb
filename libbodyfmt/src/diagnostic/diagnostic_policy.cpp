#include <bodyfmt/diagnostic_policy.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/report.h>
#include <bodyfmt/rules.h>

#include "text/text_util.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace bodyfmt {

bool rule_pattern_matches(std::string_view pattern, std::string_view rule_id) {
  if (!pattern.empty() && pattern.back() == '*') {
    pattern.remove_suffix(1);
    return rule_id.substr(0, pattern.size()) == pattern;
  }
  return pattern == rule_id;
}

std::string check_rule_pattern(std::string_view pattern) {
  const auto& rules = all_rules();
  if (std::any_of(rules.begin(), rules.end(), [&](const RuleInfo& r) { return rule_pattern_matches(pattern, r.id); }))
    return {};
  std::string message = "unknown rule id '" + std::string(pattern) + "'";
  std::string_view best;
  int best_distance = 1 << 30;
  for (const RuleInfo& r : rules) {
    int d = text::edit_distance(pattern, r.id);
    if (d < best_distance) best_distance = d, best = r.id;
  }
  const int allowed = std::max<int>(2, static_cast<int>(pattern.size()) / 3);
  if (!best.empty() && best_distance <= allowed)
    message += "; did you mean '" + std::string(best) + "'?";
  else
    message += " (bodycheck --list-rules lists them)";
  return message;
}

// ---------------------------------------------------------------------------------------------
// Suppressions

namespace {

/// Position of a YAML comment `#` in `line` (at the start or after a blank, outside quotes),
/// or npos.
std::size_t comment_start(std::string_view line) {
  bool in_single = false, in_double = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_double) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_double = false;
    } else if (in_single) {
      if (c == '\'') in_single = false;
    } else if (c == '"' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t' || line[i - 1] == '[' ||
                            line[i - 1] == '{' || line[i - 1] == ',' || line[i - 1] == ':')) {
      in_double = true;
    } else if (c == '\'' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t' || line[i - 1] == '[' ||
                             line[i - 1] == '{' || line[i - 1] == ',' || line[i - 1] == ':')) {
      in_single = true;
    } else if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
      return i;
    }
  }
  return std::string_view::npos;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

/// The rule ids of a `bodycheck: disable=A,B` comment body (after `#`), each with its offset
/// in `comment`, or empty.
std::vector<std::pair<std::string, std::size_t>> parse_directive(const std::string_view body) {
  std::string_view comment = trim(body);
  constexpr std::string_view kTag = "bodycheck:";
  if (comment.substr(0, kTag.size()) != kTag) return {};
  comment = trim(comment.substr(kTag.size()));
  constexpr std::string_view kDisable = "disable";
  if (comment.substr(0, kDisable.size()) != kDisable) return {};
  comment = trim(comment.substr(kDisable.size()));
  if (comment.empty() || comment.front() != '=') return {};
  comment = comment.substr(1);
  std::vector<std::pair<std::string, std::size_t>> ids;
  auto add = [&](std::string_view id) {
    ids.emplace_back(std::string(id), static_cast<std::size_t>(id.data() - body.data()));
  };
  std::size_t start = 0;
  while (start <= comment.size()) {
    std::size_t comma = comment.find(',', start);
    if (comma == std::string_view::npos) comma = comment.size();
    std::string_view id = trim(comment.substr(start, comma - start));
    // Anything after the id list (a blank and free text) is an explanation, not an id.
    std::size_t blank = id.find_first_of(" \t");
    if (blank != std::string_view::npos) {
      add(id.substr(0, blank));
      break;
    }
    if (!id.empty()) add(id);
    start = comma + 1;
  }
  return ids;
}

}  // namespace

Suppressions Suppressions::from_text(std::string_view text) {
  Suppressions result;
  std::vector<std::size_t> pending;
  int line_number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    result.add_line(text.substr(pos, end - pos), ++line_number, pending);
    pos = end + 1;
  }
  return result;
}

Suppressions Suppressions::from_stream(std::istream& in) {
  // Line by line: a 100,000-link model is not held a second time to find a few comments.
  Suppressions result;
  std::vector<std::size_t> pending;
  int line_number = 0;
  std::string line;
  while (std::getline(in, line)) result.add_line(line, ++line_number, pending);
  return result;
}

void Suppressions::add_line(std::string_view line, int line_number, std::vector<std::size_t>& pending) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const std::size_t hash = line.find('#') == std::string_view::npos ? std::string_view::npos : comment_start(line);
  std::vector<std::size_t> ids;
  if (hash != std::string_view::npos) {
    for (auto& [id, offset] : parse_directive(line.substr(hash + 1))) {
      ids.push_back(directives_.size());
      directives_.push_back({std::move(id), line_number, static_cast<int>(hash + 1 + offset) + 1});
    }
  }
  // A comment-only line covers the next content line.
  const bool comment_only = hash != std::string_view::npos && trim(line.substr(0, hash)).empty();
  if (comment_only && !ids.empty()) {
    pending.insert(pending.end(), ids.begin(), ids.end());
    return;
  }
  if (!pending.empty() || !ids.empty()) {
    auto& covered = by_line_[line_number];
    covered.insert(covered.end(), pending.begin(), pending.end());
    covered.insert(covered.end(), ids.begin(), ids.end());
    pending.clear();
  }
}

bool Suppressions::suppresses(int line, std::string_view rule_id) {
  auto it = by_line_.find(line);
  if (it == by_line_.end()) return false;
  bool suppressed = false;
  for (std::size_t i : it->second) {
    if (!rule_pattern_matches(directives_[i].id, rule_id)) continue;
    directives_[i].used = true;
    suppressed = true;
  }
  return suppressed;
}

// ---------------------------------------------------------------------------------------------
// DiagnosticPolicy

DiagnosticPolicy::DiagnosticPolicy(DiagnosticSink& inner, PolicyOptions options)
    : inner_(inner), options_(std::move(options)) {}

bool DiagnosticPolicy::enabled(std::string_view rule_id) const {
  auto matches = [&](const std::vector<std::string>& patterns) {
    return std::any_of(patterns.begin(), patterns.end(),
                       [&](const std::string& p) { return rule_pattern_matches(p, rule_id); });
  };
  return !matches(options_.disable) || matches(options_.enable);
}

void DiagnosticPolicy::set_suppressions(const std::string& file, Suppressions suppressions) {
  suppressions_[file] = std::move(suppressions);
}

Suppressions& DiagnosticPolicy::suppressions_for(const std::string& file) {
  auto it = suppressions_.find(file);
  if (it != suppressions_.end()) return it->second;
  Suppressions s;
  try {
    // Never a FIFO or a device (a pipe the front read already would block here); the loader
    // applied the size limit to the same file.
    std::string why;
    if (std::optional<std::string> text = read_regular_file(file, std::numeric_limits<std::uintmax_t>::max(), why)) {
      std::istringstream in(std::move(*text));
      s = Suppressions::from_stream(in);
    }
  } catch (...) {
    // Unreadable: no suppressions. The loader reports the file itself.
  }
  return suppressions_.emplace(file, std::move(s)).first->second;
}

void DiagnosticPolicy::report(Diagnostic d) {
  try {
    if (d.severity != Severity::kFatal) {
      auto cached = enabled_cache_.find(d.rule_id);
      if (cached == enabled_cache_.end()) cached = enabled_cache_.emplace(d.rule_id, enabled(d.rule_id)).first;
      if (!cached->second) {
        ++disabled_;
        return;
      }
      if (options_.inline_suppressions && !d.rule_id.empty()) {
        bool suppressed = false;
        if (d.location.known() && !d.location.file.empty())
          suppressed = suppressions_for(d.location.file).suppresses(d.location.line, d.rule_id);
        if (!suppressed && d.via && d.via->known() && !d.via->file.empty())
          suppressed = suppressions_for(d.via->file).suppresses(d.via->line, d.rule_id);
        if (suppressed) {
          ++suppressed_;
          return;
        }
      }
      if (!options_.severities.empty()) {
        auto set = severity_cache_.find(d.rule_id);
        if (set == severity_cache_.end()) {
          std::optional<Severity> chosen;
          for (const auto& [pattern, severity] : options_.severities)
            if (rule_pattern_matches(pattern, d.rule_id)) chosen = severity;
          set = severity_cache_.emplace(d.rule_id, chosen).first;
        }
        if (set->second) d.severity = *set->second;
      }
      if (options_.strict && d.severity < Severity::kError &&
          (rule_pattern_matches("export-loss*", d.rule_id) || d.rule_id == "export-value-changed"))
        d.severity = Severity::kError;
      if (options_.werror && d.severity == Severity::kWarning) d.severity = Severity::kError;
    }
    ++counts_[static_cast<int>(d.severity)];
    ++by_rule_[d.rule_id];
  } catch (...) {
    // Out of memory in the bookkeeping: still forward the diagnostic.
  }
  inner_.report(std::move(d));
}

void DiagnosticPolicy::report_suppression_problems(const std::string& file) {
  if (!options_.inline_suppressions) return;
  // Copied: reporting below may itself consult (and mark) this file's suppressions.
  const std::vector<Suppressions::Directive> directives = suppressions_for(file).directives();
  for (const Suppressions::Directive& d : directives) {
    const SourceLocation at{file, d.line, d.column};
    const std::string unknown = check_rule_pattern(d.id);
    if (!unknown.empty()) {
      report(make_diagnostic("suppression-unknown-rule", at, "this suppression comment names an " + unknown,
                             "a mistyped id suppresses nothing; bodycheck --list-rules lists the ids"));
    } else if (!d.used && enabled(d.id)) {
      report(make_diagnostic("suppression-unused", at,
                             "'# bodycheck: disable=" + d.id + "' suppresses nothing on the line it covers",
                             "remove it: a stale suppression would hide a new finding on that line"));
    }
  }
}

// ---------------------------------------------------------------------------------------------
}  // namespace bodyfmt
