#pragma once
/// The keys of every Body-format node (body-format-spec §2-§12): what each means, its unit,
/// its default and the values it takes. One table: the loader takes its lists of known keys
/// from it (the did-you-mean of `load-unknown-key`), bodyls answers hover and completion from
/// it, and keys_doc prints it as docs/keys.md.

#include <bodyfmt/export.h>

#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// How the loader reads a number under the key (body-format-spec §3).
enum class AngleRule {
  kNone,             ///< not an angle
  kAngle,            ///< in the file's angle unit
  kAngleIfRevolute,  ///< in the angle unit on a revolute joint, else metres (per second)
  kAxisAngle,        ///< the 4th number of each [x, y, z, angle] is in the angle unit
};

struct BodyKey {
  std::string_view name;    ///< snake_case, as the loader looks it up first
  std::string_view legacy;  ///< the other spellings the loader accepts, comma-separated, or ""
  std::string_view meaning;
  std::string_view unit;                 ///< "m", "kg", "angle", ... or "" for none
  std::string_view default_value;        ///< "" when the key has none (required, or nothing happens)
  std::vector<std::string_view> values;  ///< the enumeration's values, when it is one
  AngleRule angle = AngleRule::kNone;
};

/// The keys of one kind of node.
struct BodyNode {
  /// "body", "link", "geometry:Box", "element:Shape", "device:Camera", ... A "device:X" node
  /// lists the common device keys and X's parameters; the loader checks the common ones
  /// ("device") against the mapping, the parameters are read by type.
  std::string_view id;
  std::string_view title;  ///< how docs/keys.md heads it
  std::vector<BodyKey> keys;
  /// The keys' names in table order: the loader's list of known keys for this node.
  std::vector<std::string_view> names;
};

/// Every node kind, in the order docs/keys.md lists them.
const std::vector<BodyNode>& body_nodes();
/// The node `id`; nullptr when none has it.
const BodyNode* find_body_node(std::string_view id);
/// The key `name` of `node` under its snake_case name or a legacy spelling; nullptr if none.
const BodyKey* find_body_key(const BodyNode& node, std::string_view name);
/// The names of the node's keys (BodyNode::names); an empty list for an unknown id.
const std::vector<std::string_view>& body_key_names(std::string_view id);

/// Values that select a node kind: the element types (those the loader reads, the scene-only
/// ones it accepts, and the core devices: its did-you-mean candidates), the geometry types, and
/// the core device types (a node of one of these is a device).
const std::vector<std::string_view>& element_type_names();
const std::vector<std::string_view>& geometry_type_names();
const std::vector<std::string_view>& device_type_names();

/// One key as a line of Markdown: meaning, unit, default, values. `angle_unit` ("degree",
/// "radian") stands for the word "angle" in the unit, as a file that names its unit reads it.
std::string describe_body_key(const BodyKey& key, std::string_view angle_unit = "angle");
/// docs/keys.md: every node's keys as Markdown tables.
std::string body_keys_markdown();

}  // namespace bodyfmt
#pragma GCC visibility pop
