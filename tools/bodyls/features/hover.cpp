// hover (language_features.h): a key's meaning, unit (an angle's in the file's unit) and
// default from the key table, and where docs/keys.md has it; an angle's value in degrees and
// radians as the file reads it; a link's mass and world frame. In Markdown and plain text.
#include "cursor.h"
#include "hover_text.h"
#include "language_features.h"
#include "link_facts.h"
#include "outline.h"
#include "schema.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/yaml.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <optional>
#include <string>

namespace bodyfmt::lsp {
namespace {

std::optional<HoverText> key_hover(const Outline& o, int mapping, const OutlineEntry& entry) {
  const std::string kind = node_kind(o, mapping);
  HoverText out;
  if (kind == "elements") {
    if (element_kind(entry.key).empty()) return std::nullopt;
    out.bold(entry.key).text(": an element of type " + entry.key + " (elements written as a mapping of types)");
    return out;
  }
  if (kind == "geometry" && entry.key == "type") return out.bold("type").text(": the geometry's type");
  const BodyNode* node = table_node(kind);
  if (!node) return std::nullopt;
  // The key table's headings are docs/keys.md's, which is installed (share/doc/bodyfmt/docs).
  const std::string see = "docs/keys.md, \"" + std::string(node->title) + "\"";
  if (const BodyKey* key = find_body_key(*node, entry.key)) {
    out.bold(key->name);
    if (!key->legacy.empty()) out.text(" (also ").code(key->legacy).text(")");
    out.text(" — " + std::string(node->title)).paragraph();
    if (key->angle == AngleRule::kNone) {
      out.text(describe_body_key(*key));
    } else {
      const AngleMode mode = angle_mode(o);
      out.text(describe_body_key(*key, angle_unit_word(mode)));
      out.text(mode.refused ? " (the file does not load: " + mode.why + ")" : " (" + mode.why + ")");
    }
    if (key->name != entry.key && key->legacy.find(entry.key) != std::string_view::npos)
      out.paragraph().text("A legacy spelling: write ").code(key->name).text(".");
    out.paragraph().text("More in " + see + ".");
    return out;
  }
  out.bold(entry.key).text(" is not a key of " + std::string(node->title));
  const std::string_view guess = did_you_mean(entry.key, node->names);
  if (!guess.empty())
    out.text("; did you mean ").code(guess).text("?");
  else
    out.text(": Choreonoid keeps it as info and does not read it.");
  out.paragraph().text("Its keys: " + see + ".");
  return out;
}

/// The whole scalar as a number, as the loader's lenient read would take its leading number.
std::optional<double> number_of(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || errno == ERANGE) return std::nullopt;
  return v;
}

std::optional<HoverText> angle_hover(const Outline& o, int scalar, int mapping, const OutlineEntry& entry) {
  const BodyNode* node = table_node(node_kind(o, mapping));
  if (!node) return std::nullopt;
  const BodyKey* key = find_body_key(*node, entry.key);
  if (!key || key->angle == AngleRule::kNone) return std::nullopt;
  const std::optional<double> value = number_of(o.node(scalar).scalar);
  if (!value) return std::nullopt;
  std::string why;
  const std::string written = o.node(scalar).scalar;
  HoverText out;
  if (!reads_as_angle(o, scalar, *key, mapping, why))
    return out.code(written).text(" under ").bold(key->name).text(": " + why + ", read as written");
  const AngleMode mode = angle_mode(o);
  if (mode.refused) return out.code(written).text(": the file does not load (" + mode.why + ")");
  const double radians = mode.degrees ? *value * kPi / 180 : *value;
  const double degrees = mode.degrees ? *value : *value * 180 / kPi;
  out.code(written).text(" under ").bold(key->name);
  out.text(fmt::format(" is an angle in {} ({}):", mode.degrees ? "degrees" : "radians", mode.why)).paragraph();
  return out.text(fmt::format("{:.10g}° = {:.10g} rad", degrees, radians));
}

}  // namespace

std::optional<Hover> hover(const Document& document, TextPoint point) {
  const Outline outline(document.text);
  const TextIndex index(document.text);
  const std::size_t offset = index.offset(point);
  const AtCursor at = locate(outline, offset);
  if (at.key) {
    if (auto text = key_hover(outline, at.key_mapping, *at.key))
      return Hover{text->markdown(), text->plain(), index.range(at.key->key_begin, at.key->key_end)};
    return std::nullopt;
  }
  if (at.value < 0 || !at.holder) return std::nullopt;
  const OutlineNode& value = outline.node(at.value);
  const TextRange range = index.range(value.begin, value.end);
  const std::string kind = node_kind(outline, at.holder_mapping);
  if (((is_link_kind(kind) && at.holder->key == "name") || names_a_link(kind, at.holder->key)) &&
      value.kind == OutlineNode::kScalar) {
    if (auto text = link_hover(document, value.scalar)) return Hover{text->markdown(), text->plain(), range};
    return std::nullopt;
  }
  if (value.kind == OutlineNode::kScalar)
    if (auto text = angle_hover(outline, at.value, at.holder_mapping, *at.holder))
      return Hover{text->markdown(), text->plain(), range};
  return std::nullopt;
}

}  // namespace bodyfmt::lsp
