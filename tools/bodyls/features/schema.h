#pragma once
// What a place in the outline is in Body-format terms: the key table's node kind of a mapping
// (link, element:Shape, geometry:Box, ...), and how the file reads its angles.

#include "outline.h"

#include <bodyfmt/body_keys.h>

#include <optional>
#include <string>
#include <string_view>

namespace bodyfmt::lsp {

/// The node kind of mapping `node` (an id of the key table, body_nodes()), or one of two ids
/// that are not in it: "elements" (an elements mapping that maps types to nodes) and
/// "geometry" (a geometry whose type is not known yet). Empty when the place is no node the
/// format knows.
std::string node_kind(const Outline& outline, int node);

/// A link, SubBody or ContinuousTrack node of `links`.
inline bool is_link_kind(std::string_view kind) { return kind == "link" || kind.rfind("link:", 0) == 0; }
/// A device of any type.
inline bool is_device_kind(std::string_view kind) { return kind == "device" || kind.rfind("device:", 0) == 0; }

/// Whether key `key` of a node of kind `kind` names a link, other than a link's own `name`:
/// a link's parent, the root_link, an extra joint's link1_name and link2_name.
bool names_a_link(std::string_view kind, std::string_view key);

/// The element kind a `type` value selects ("element:Shape", "device", ...); empty if none.
std::string element_kind(std::string_view type);

/// The key table's node of `kind`; for "geometry", nullptr.
const BodyNode* table_node(std::string_view kind);

/// How the file's header makes it read angles (body-format-spec §2.1, §3).
struct AngleMode {
  bool degrees = true;
  bool refused = false;  ///< radian in format 2.0: the loader refuses the file
  std::string why;       ///< "format 2.0", "format 1.0, angle_unit: radian", ...
};
AngleMode angle_mode(const Outline& outline);
/// The word for "angle" in a key's unit as the file reads its angles: "degree", "radian", or
/// "angle" when the file does not load.
std::string angle_unit_word(const AngleMode& mode);

/// Whether the number `scalar` (a node of the outline) is read as an angle, given the key it
/// is under, that key's rule and the mapping that holds the key. Why not, in `why`.
bool reads_as_angle(const Outline& outline, int scalar, const BodyKey& key, int mapping, std::string& why);

}  // namespace bodyfmt::lsp
