#include <bodyfmt/rules.h>

#include <algorithm>

namespace bodyfmt {
namespace {

constexpr Severity E = Severity::kError;
constexpr Severity W = Severity::kWarning;
constexpr Severity N = Severity::kNote;
constexpr Severity F = Severity::kFatal;

std::vector<RuleInfo> make_table() {
  std::vector<RuleInfo> rules = {
      // I/O and internal
      {"io-read", F, "a file cannot be opened or read", "nothing can be checked without the text", ""},
      {"config-invalid", E, "a .bodycheck.yaml is malformed (syntax, unknown key, bad value or rule id)", "bodycheck cannot know how strict to be, so it checks nothing under it", ""},
      {"internal-error", F, "an unexpected internal failure", "a bug in bodyfmt; please report it with the file", ""},
      // YAML layer (body-format-spec §1)
      {"yaml-syntax", F, "the text is not valid YAML", "Choreonoid's libyaml reader refuses the file", ""},
      {"yaml-duplicate-key", W, "a mapping repeats a key; the last one wins", "the earlier value is silently lost in Choreonoid", ""},
      {"yaml-anchor-redefined", E, "an anchor name is defined twice", "Choreonoid refuses the file (Anchor is duplicated)", ""},
      {"yaml-undefined-alias", E, "an alias names no anchor", "Choreonoid refuses the file (Anchor is not defined)", ""},
      {"yaml-recursive-alias", F, "an alias refers to the node that contains it", "the document would be infinite", ""},
      {"yaml-merge-invalid", E, "a `<<` merge value is not a mapping or a list of mappings", "Choreonoid refuses the file", ""},
      {"yaml-empty-key", E, "a mapping key is empty", "Choreonoid refuses the file (empty key)", ""},
      {"yaml-complex-key", E, "a mapping key is not a scalar", "Choreonoid's reader only supports scalar keys", ""},
      {"yaml-alias-expansion", F, "alias expansion exceeds the node budget", "a \"billion laughs\" document would exhaust memory in any consumer", "LoadOptions::max_expanded_yaml_nodes (default 10,000,000)"},
      {"yaml-depth", F, "nesting exceeds the depth budget", "deep nesting exhausts the stack of recursive readers", "LoadOptions::max_yaml_depth (default 200)"},
      // Body header and keys (§2, §14)
      {"load-top-level", F, "the document is not a mapping", "a body file is a mapping of header keys", ""},
      {"load-format", F, "`format` is missing or not ChoreonoidBody", "Choreonoid refuses the file", ""},
      {"load-format-version", F, "`format_version` is missing or unsupported (>= 2.1)", "Choreonoid refuses the file", ""},
      {"load-angle-unit", F, "`angle_unit` is neither degree nor radian", "Choreonoid refuses the file", ""},
      {"load-wrapper", F, "a wrapper file (model_file without format)", "not supported by bodyfmt", ""},
      {"load-no-links", F, "no links are defined", "a body needs at least one link", ""},
      {"load-legacy-key", W, "a legacy camelCase key or value", "it loads, but the modern snake_case spelling is the documented one", ""},
      {"load-unknown-key", W, "an unknown key close to a known one (probable typo)", "Choreonoid ignores it silently, so the intended value is lost", "edit distance <= 1 (4-7 characters) or 2 (8+ characters), transpositions count once"},
      {"load-info-key", N, "a key the format does not define", "Choreonoid keeps it as info for other subsystems", ""},
      {"load-ignored-key", W, "a key Choreonoid reads under another name or not at all", "its value has no effect", ""},
      {"load-ignored-value", W, "a value Choreonoid ignores (wrong type for an optional key)", "the default is used instead, silently in Choreonoid", ""},
      {"load-lenient-number", W, "a number with trailing garbage, e.g. `0.t`", "Choreonoid reads the numeric prefix silently", ""},
      {"load-number", E, "a value must be a number", "Choreonoid refuses the file", ""},
      {"load-bool", E, "a value must be a boolean", "Choreonoid refuses the file", ""},
      {"load-type", E, "a value has the wrong YAML type", "Choreonoid refuses the file or ignores the node", ""},
      {"load-type-mismatch", E, "an inner `type` differs from the type key of a type-keyed mapping", "Choreonoid refuses the file", ""},
      {"load-missing-key", E, "a required key is missing", "Choreonoid refuses the file", ""},
      {"load-vector-size", E, "a vector has the wrong number of elements", "Choreonoid refuses the file", ""},
      {"load-rotation-axis", E, "a rotation axis is the zero vector", "Choreonoid refuses the file", ""},
      {"load-inertia-size", E, "an inertia has neither 6 nor 9 elements", "Choreonoid refuses the file", ""},
      {"load-axis", E, "an illegal joint axis symbol", "Choreonoid refuses the file", ""},
      {"load-range", E, "an invalid joint range or limit", "Choreonoid refuses the file", ""},
      {"load-joint-type", E, "an illegal joint type", "Choreonoid refuses the file", ""},
      {"load-actuation-mode", E, "an illegal actuation mode", "Choreonoid refuses the file", ""},
      {"load-angle-on-prismatic", W, "joint_angle on a prismatic joint in a degree file", "Choreonoid converts it from degrees", ""},
      {"load-link-name", E, "a link has no name", "it cannot be referenced as a parent", ""},
      {"load-link-type", E, "an unknown node type in `links`", "Choreonoid refuses the file", ""},
      {"load-mass-ignored", W, "mass keys where Choreonoid ignores them (Transform, SubBody)", "the mass the author meant is not simulated", ""},
      {"load-default-mass", N, "a link has no mass data and gets 1 kg with identity inertia", "Choreonoid simulates these defaults; other engines differ", ""},
      {"load-import", N, "`import` only adds info keys", "model keys inside it have no effect", ""},
      {"load-scene-node", N, "a scene-only node (light, camera, fog) in a body", "it has no meaning for the body", ""},
      {"load-unknown-node-type", E, "an unknown element node type", "Choreonoid refuses the file (a warning when is_optional)", ""},
      {"load-plugin-node", W, "a node type that needs a Choreonoid plugin", "kept as an opaque device; Choreonoid refuses the file without the plugin", ""},
      {"load-visual-collision-conflict", E, "Visual inside Collision or the reverse", "Choreonoid refuses the file", ""},
      {"load-continuous-track", E, "an invalid ContinuousTrack node", "Choreonoid refuses the file", ""},
      {"load-uri", E, "a URI cannot be resolved (scheme, package or path variable)", "the resource cannot be loaded", ""},
      {"units-radian-in-2.0", F, "`angle_unit: radian` in format 2.0", "Choreonoid refuses radian mode in 2.0", ""},
      // Tree (§5)
      {"structure-duplicate-link", E, "two links share a name", "Choreonoid refuses the file", ""},
      {"structure-duplicate-joint-name", E, "two joints share a name", "Choreonoid refuses the file", ""},
      {"structure-root-link", F, "`root_link` names no link", "Choreonoid refuses the file", ""},
      {"structure-root-parent", E, "the root link has a parent", "the parent is ignored", ""},
      {"structure-no-parent", E, "a non-root link has no parent", "Choreonoid refuses the file", ""},
      {"structure-unknown-parent", E, "a parent names no link", "Choreonoid refuses the file", ""},
      {"structure-cycle", E, "parents form a cycle", "Choreonoid refuses the file", ""},
      {"structure-unreachable", E, "a link is not connected to the root", "it is not part of the body", ""},
      // Geometry (§9)
      {"geometry-invalid-size", E, "a non-positive size, radius or height", "Choreonoid refuses the shape", ""},
      {"geometry-degenerate", E, "an Extrusion, ElevationGrid or mesh that produces no valid surface", "Choreonoid crashes or drops the shape", ""},
      {"geometry-index-out-of-range", E, "a face index outside the vertex list", "Choreonoid refuses the file", ""},
      {"geometry-unterminated-polygon", W, "the last IndexedFaceSet polygon is not closed by -1", "Choreonoid silently drops it", ""},
      {"geometry-unknown-type", E, "an unknown geometry type", "Choreonoid refuses the file", ""},
      // Devices (§10)
      {"device-camera-dropped", W, "a Camera without a valid format", "Choreonoid silently drops the camera", ""},
      {"device-optical-frame", E, "an unknown optical frame", "Choreonoid refuses the file", ""},
      // Extra joints (§12)
      {"extra-joint-link", E, "an extra joint names no link", "Choreonoid refuses the file", ""},
      {"extra-joint-type", E, "an extra joint type is missing or unknown", "Choreonoid refuses the file", ""},
      {"extra-joint-axis", E, "an extra joint axis is the zero vector", "the joint has no direction", ""},
      // Resources (§9.1-9.4, §11.2)
      {"resource-missing", E, "a resource file cannot be read", "its geometry is missing", ""},
      {"resource-fragment", E, "a YAML fragment anchor is not found", "Choreonoid refuses the file", ""},
      {"resource-unsupported", E, "a Resource node where none can be read", "its geometry is missing", ""},
      {"subbody-missing", E, "a SubBody file cannot be read", "its links are missing", ""},
      {"subbody-load", E, "a SubBody file cannot be loaded", "its links are missing", ""},
      {"subbody-recursion", E, "SubBody includes form a cycle", "loading would never end", ""},
      {"mesh-file-missing", E, "a mesh file does not exist", "its geometry is missing", ""},
      {"mesh-file-unreadable", E, "a mesh file cannot be read", "its geometry is missing", ""},
      {"mesh-format-unsupported", E, "a mesh file extension no reader supports", "its geometry is missing", ""},
      {"mesh-parse", E, "a mesh file is malformed", "its geometry is missing or partial", ""},
      {"mesh-node-not-found", E, "the selected node is not in the mesh file", "Choreonoid refuses the file", ""},
      {"mesh-inline-cycle", E, "VRML Inline files include each other", "loading would never end", ""},
      {"mesh-invalid-geometry", E, "a mesh file has invalid geometry", "part of it is dropped", ""},
      {"mesh-empty", W, "a mesh file or node has no triangles", "nothing is drawn or collides", ""},
  };
  std::sort(rules.begin(), rules.end(), [](const RuleInfo& a, const RuleInfo& b) { return a.id < b.id; });
  return rules;
}

}  // namespace

const std::vector<RuleInfo>& all_rules() {
  static const std::vector<RuleInfo> rules = make_table();
  return rules;
}

const RuleInfo* find_rule(std::string_view id) {
  const auto& rules = all_rules();
  auto it = std::lower_bound(rules.begin(), rules.end(), id,
                             [](const RuleInfo& r, std::string_view key) { return r.id < key; });
  return it != rules.end() && it->id == id ? &*it : nullptr;
}

}  // namespace bodyfmt
