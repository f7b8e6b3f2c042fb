#include "change_report.h"

#include <bodyfmt/text.h>

#include <fmt/format.h>

namespace bodyfmt::tools {
namespace {

std::string_view kind_name(ChangeKind kind) {
  switch (kind) {
    case ChangeKind::kAdded: return "added";
    case ChangeKind::kRemoved: return "removed";
    case ChangeKind::kChanged: return "changed";
  }
  return "changed";
}

std::string where(const SourceLocation& at, const std::string& fallback) {
  const std::string file = at.file.empty() ? fallback : at.file.str();
  return at.known() ? fmt::format("{}:{}:{}", file, at.line, at.column) : file;
}

std::string subject(const ModelChange& c) {
  const std::string derived = c.derived ? " (derived)" : "";
  if (c.field == "link") return fmt::format("link '{}'", c.link);
  return fmt::format("{}{}{}", c.link.empty() ? std::string("model") : "link '" + c.link + "'", ": " + c.field,
                     derived);
}

std::string json_side(const std::string& value, const SourceLocation& at, const std::string& fallback, bool present) {
  if (!present) return "null";
  return fmt::format(R"({{"value": {}, "file": {}, "line": {}, "column": {}}})", text::json_quote(value),
                     text::json_quote(at.file.empty() ? fallback : at.file.str()), at.line, at.column);
}

}  // namespace

void write_text(std::ostream& out, const std::vector<ModelChange>& changes, const std::string& old_name,
                const std::string& new_name) {
  std::string group = "\x01";
  for (const ModelChange& c : changes) {
    if (c.link != group) {
      group = c.link;
      const std::string& file = c.kind == ChangeKind::kRemoved && c.field == "link" ? old_name : new_name;
      out << (group.empty() ? fmt::format("{}: In the model:\n", file)
                            : fmt::format("{}: In link '{}':\n", file, group));
    }
    switch (c.kind) {
      case ChangeKind::kChanged:
        out << fmt::format("{}: changed: {}: {} -> {}\n", where(c.new_source, new_name), subject(c), c.old_value,
                           c.new_value);
        out << fmt::format("{}: note: was {}\n", where(c.old_source, old_name), c.old_value);
        break;
      case ChangeKind::kAdded:
        out << fmt::format("{}: added: {}: {}\n", where(c.new_source, new_name), subject(c), c.new_value);
        break;
      case ChangeKind::kRemoved:
        out << fmt::format("{}: removed: {}: {}\n", where(c.old_source, old_name), subject(c), c.old_value);
        break;
    }
  }
}

void write_json(std::ostream& out, const std::vector<ModelChange>& changes, const std::string& old_name,
                const std::string& new_name, double tolerance) {
  std::size_t counts[3] = {0, 0, 0};
  out << "{\n  \"version\": 1,\n";
  out << fmt::format("  \"tool\": {{\"name\": \"bodydiff\", \"version\": \"{}\"}},\n", BODYFMT_VERSION);
  out << fmt::format("  \"old\": {},\n  \"new\": {},\n  \"tolerance\": {},\n", text::json_quote(old_name),
                     text::json_quote(new_name), tolerance);
  out << "  \"changes\": [";
  for (std::size_t i = 0; i < changes.size(); ++i) {
    const ModelChange& c = changes[i];
    ++counts[static_cast<int>(c.kind)];
    out << (i ? ",\n    " : "\n    ");
    out << fmt::format(R"({{"kind": "{}", "link": {}, "field": {}, "derived": {}, "old": {}, "new": {}}})",
                       kind_name(c.kind), c.link.empty() ? "null" : text::json_quote(c.link), text::json_quote(c.field),
                       c.derived, json_side(c.old_value, c.old_source, old_name, c.kind != ChangeKind::kAdded),
                       json_side(c.new_value, c.new_source, new_name, c.kind != ChangeKind::kRemoved));
  }
  out << (changes.empty() ? "],\n" : "\n  ],\n");
  out << fmt::format("  \"summary\": {{\"changes\": {}, \"added\": {}, \"removed\": {}, \"changed\": {}}}\n}}\n",
                     changes.size(), counts[0], counts[1], counts[2]);
}

void name_old_side(std::vector<ModelChange>& changes, const std::string& from, const std::string& to) {
  for (ModelChange& c : changes)
    if (c.old_source.file == from) c.old_source.file = FileName(to);
}

void name_sides(std::vector<ModelChange>& changes, const std::string& path) {
  name_old_side(changes, path, "a/" + path);
  for (ModelChange& c : changes)
    if (c.new_source.file == path) c.new_source.file = FileName("b/" + path);
}

}  // namespace bodyfmt::tools
