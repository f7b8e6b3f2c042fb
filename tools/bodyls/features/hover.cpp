// hover (language_features.h): a key's meaning, unit and default from the key table; an
// angle's value in degrees and radians as the file reads it; a link's mass and world frame.
#include "cursor.h"
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

std::optional<std::string> key_markdown(const Outline& o, int mapping, const OutlineEntry& entry) {
  const std::string kind = node_kind(o, mapping);
  if (kind == "elements") {
    if (!element_kind(entry.key).empty())
      return "**" + entry.key + "**: an element of type " + entry.key + " (elements written as a mapping of types)";
    return std::nullopt;
  }
  if (kind == "geometry" && entry.key == "type") return std::string("**type**: the geometry's type");
  const BodyNode* node = table_node(kind);
  if (!node) return std::nullopt;
  if (const BodyKey* key = find_body_key(*node, entry.key)) {
    std::string md = "**" + std::string(key->name) + "**";
    if (!key->legacy.empty()) md += " (also `" + std::string(key->legacy) + "`)";
    md += " — " + std::string(node->title) + "\n\n" + describe_body_key(*key);
    if (key->name != entry.key && key->legacy.find(entry.key) != std::string_view::npos)
      md += "\n\nA legacy spelling: write `" + std::string(key->name) + "`.";
    return md;
  }
  std::string md = "**" + entry.key + "** is not a key of " + std::string(node->title);
  const std::string_view guess = did_you_mean(entry.key, node->names);
  if (!guess.empty())
    md += "; did you mean `" + std::string(guess) + "`?";
  else
    md += ": Choreonoid keeps it as info and does not read it.";
  return md;
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

std::optional<std::string> angle_markdown(const Outline& o, int scalar, int mapping, const OutlineEntry& entry) {
  const BodyNode* node = table_node(node_kind(o, mapping));
  if (!node) return std::nullopt;
  const BodyKey* key = find_body_key(*node, entry.key);
  if (!key || key->angle == AngleRule::kNone) return std::nullopt;
  const std::optional<double> value = number_of(o.node(scalar).scalar);
  if (!value) return std::nullopt;
  std::string why;
  const std::string written = o.node(scalar).scalar;
  if (!reads_as_angle(o, scalar, *key, mapping, why))
    return "`" + written + "` under **" + std::string(key->name) + "**: " + why + ", read as written";
  const AngleMode mode = angle_mode(o);
  if (mode.refused) return "`" + written + "`: the file does not load (" + mode.why + ")";
  const double radians = mode.degrees ? *value * kPi / 180 : *value;
  const double degrees = mode.degrees ? *value : *value * 180 / kPi;
  return fmt::format("`{}` under **{}** is an angle in {} ({}):\n\n{:.10g}° = {:.10g} rad", written, key->name,
                     mode.degrees ? "degrees" : "radians", mode.why, degrees, radians);
}

}  // namespace

std::optional<Hover> hover(const Document& document, TextPoint point) {
  const Outline outline(document.text);
  const TextIndex index(document.text);
  const std::size_t offset = index.offset(point);
  const AtCursor at = locate(outline, offset);
  if (at.key) {
    if (auto md = key_markdown(outline, at.key_mapping, *at.key))
      return Hover{*md, index.range(at.key->key_begin, at.key->key_end)};
    return std::nullopt;
  }
  if (at.value < 0 || !at.holder) return std::nullopt;
  const OutlineNode& value = outline.node(at.value);
  const TextRange range = index.range(value.begin, value.end);
  const std::string kind = node_kind(outline, at.holder_mapping);
  if (((is_link_kind(kind) && at.holder->key == "name") || names_a_link(kind, at.holder->key)) &&
      value.kind == OutlineNode::kScalar) {
    if (auto md = link_markdown(document, value.scalar)) return Hover{*md, range};
    return std::nullopt;
  }
  if (value.kind == OutlineNode::kScalar)
    if (auto md = angle_markdown(outline, at.value, at.holder_mapping, *at.holder)) return Hover{*md, range};
  return std::nullopt;
}

}  // namespace bodyfmt::lsp
