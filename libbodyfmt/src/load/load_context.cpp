#include "load/load_context.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace bodyfmt::detail {

namespace {

std::optional<FixIt> edit_span(const SourceLocation& at, const yaml::TextSpan& span, std::string_view original,
                               std::string replacement, FixSafety safety) {
  if (!span.editable()) return std::nullopt;
  FixIt fix;
  fix.file = at.file;
  fix.begin = span.begin;
  fix.end = span.end;
  fix.line = at.line;
  fix.column = span.column;
  fix.original = original;
  fix.replacement = std::move(replacement);
  fix.safety = safety;
  return fix;
}

}  // namespace

std::optional<FixIt> edit_value(const yaml::Node& node, std::string replacement, FixSafety safety) {
  if (!node.is_scalar()) return std::nullopt;
  return edit_span(node.location, node.span, node.scalar(), std::move(replacement), safety);
}

std::optional<FixIt> edit_key(const yaml::MapEntry& entry, std::string replacement, FixSafety safety) {
  return edit_span(entry.key_location, entry.key_span, entry.key, std::move(replacement), safety);
}

std::optional<EntryLines> entry_lines(const LoadContext& ctx, const yaml::NodeRef& mapping,
                                      const yaml::MapEntry& entry) {
  if (entry.merged || mapping.alias_site || mapping.enclosing_alias || !entry.key_span.editable()) return std::nullopt;
  const std::string_view text = ctx.text;
  if (text.empty() || entry.key_location.file != ctx.text_file || entry.key_span.end > text.size()) return std::nullopt;
  EntryLines lines;
  const std::size_t key = entry.key_span.begin;
  lines.begin = key == 0 ? 0 : text.rfind('\n', key - 1) + 1;  // npos + 1 == 0: the first line
  for (std::size_t i = lines.begin; i < key; ++i)
    if (text[i] != ' ') return std::nullopt;
  lines.indent = key - lines.begin;
  auto line_end = [&](std::size_t from) {
    const std::size_t eol = text.find('\n', from);
    return eol == std::string_view::npos ? text.size() : eol + 1;
  };
  lines.end = line_end(key);
  int depth = 0;   // flow brackets open on the lines so far: a flow value may go on less indented
  char quote = 0;  // a quoted scalar open (a plain scalar's apostrophe counts too: no fix-it then)
  auto count_brackets = [&](std::size_t from, std::size_t to) {
    for (std::size_t i = from; i < to; ++i) {
      const char c = text[i];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '#' && (i == from || text[i - 1] == ' ')) {
        break;  // a comment to the end of the line
      } else if (c == '[' || c == '{') {
        ++depth;
      } else if (c == ']' || c == '}') {
        --depth;
      }
    }
  };
  count_brackets(key, lines.end);
  for (std::size_t at = lines.end; at < text.size();) {
    const std::size_t next = line_end(at);
    std::size_t first = at;
    while (first < next && text[first] == ' ') ++first;
    const bool blank = first == next || text[first] == '\n' || text[first] == '\r' || text[first] == '#';
    if (!blank && depth <= 0 && first - at <= lines.indent) break;
    if (!blank) {
      count_brackets(first, next);
      lines.end = next;
    }
    at = next;
  }
  // A quote or a bracket left open (a multi-line quoted scalar, a flow value ending further
  // down): the extent is not known for sure.
  if (depth != 0 || quote != 0) return std::nullopt;
  return lines;
}

std::string number_text(double value) {
  if (value == 0) return "0";  // no "-0"
  return fmt::format("{}", value);
}

std::string degrees_text(double radians) {
  // The loader reads a degree value d as d * kPi / 180.0: the shortest d that gives `radians`
  // back bit for bit is the model unchanged, and 45 rather than 45.00000000000001.
  const double degrees = radians * 180.0 / kPi;
  if (!std::isfinite(degrees) || degrees == 0) return number_text(degrees);
  for (int digits = 1; digits <= 17; ++digits) {
    const double shorter = std::strtod(fmt::format("{:.{}g}", degrees, digits).c_str(), nullptr);
    if (shorter * kPi / 180.0 == radians) return number_text(shorter);  // "-10", never "-1e+01"
  }
  return number_text(degrees);
}

void LoadContext::report(std::string_view rule, const yaml::NodeRef& at, std::string message, std::string hint,
                         std::vector<FixIt> fixes) {
  if (!at) return report(rule, SourceLocation{}, std::move(message), std::move(hint));
  // Point at the text responsible; when it was reached through an alias (directly or as
  // part of shared text), `via` names the alias use that led to it (style.md §2.3).
  const SourceLocation* via_site = at.alias_site != nullptr ? at.alias_site : at.enclosing_alias;
  std::optional<SourceLocation> via;
  if (via_site != nullptr) via = *via_site;
  emit(rule, at->location, std::move(via), std::move(message), std::move(hint), std::move(fixes));
}

void LoadContext::report(std::string_view rule, const SourceLocation& at, std::string message, std::string hint,
                         std::vector<FixIt> fixes) {
  emit(rule, at, std::nullopt, std::move(message), std::move(hint), std::move(fixes));
}

void LoadContext::emit(std::string_view rule, const SourceLocation& at, std::optional<SourceLocation> via,
                       std::string message, std::string hint, std::vector<FixIt> fixes) {
  if (!reported.emplace(std::string(rule), at.file, at.line, at.column, message).second) return;
  Diagnostic d = make_diagnostic(rule, at, std::move(message), std::move(hint));
  d.via = std::move(via);
  d.fixes = std::move(fixes);
  if (d.severity >= Severity::kError) ++errors;
  sink.report(std::move(d));
}

double LoadContext::angle(double value, const yaml::NodeRef& at) {
  if (degrees) return value * kPi / 180.0;
  record_upgrade(at, value);
  return value;
}

void LoadContext::record_upgrade(const yaml::NodeRef& at, double radians) {
  if (degrees || own_angle_unit || !at) return;
  std::optional<FixIt> fix = edit_value(*at, degrees_text(radians), FixSafety::kUpgrade);
  if (!fix) {
    upgrade_blockers.push_back(at->location);
    return;
  }
  // Text shared through an alias is read once per use: one edit.
  if (upgrade_fix_keys.emplace(&fix->file.str(), fix->begin, fix->end, fix->replacement).second)
    upgrade_fixes.push_back(std::move(*fix));
}

void LoadContext::note_angle(const yaml::NodeRef& at) {
  if (degrees || !at || !at->is_scalar()) return;
  // Lenient like Choreonoid's required reads (§1.2): the numeric prefix.
  const char* text = at->scalar().data();  // NUL-terminated
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end != text) record_upgrade(at, value);
}

void LoadContext::note_rotation_angles(const yaml::NodeRef& rotation) {
  if (degrees || !rotation || !rotation->is_sequence()) return;
  if (rotation->items().size() == 4 && rotation->items().front()->is_scalar()) {
    note_angle(rotation.child(rotation->items()[3]));
    return;
  }
  for (const yaml::NodeRef& item : rotation->items())
    if (item->is_sequence() && item->items().size() == 4) note_angle(rotation.child(item).child(item->items()[3]));
}

}  // namespace bodyfmt::detail
