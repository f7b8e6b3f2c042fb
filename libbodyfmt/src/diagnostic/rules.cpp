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
      {"config-invalid", E, "a .bodycheck.yaml is malformed (syntax, unknown key, bad value or rule id)",
       "bodycheck cannot know how strict to be, so it checks nothing under it", ""},
      {"internal-error", F, "an unexpected internal failure", "a bug in bodyfmt; please report it with the file", ""},
      {"lsp-findings-limited", N, "the language server shows only the first findings of a large check",
       "an editor cannot show hundreds of thousands of findings usefully, and one message of that size holds "
       "the editor up; bodycheck lists them all",
       "initializationOptions.maxDiagnostics (default 1000)"},
      // YAML layer (body-format-spec §1)
      {"yaml-syntax", F, "the text is not valid YAML", "Choreonoid's libyaml reader refuses the file", ""},
      {"yaml-duplicate-key", W, "a mapping repeats a key; the last one wins",
       "the earlier value is silently lost in Choreonoid", ""},
      {"yaml-anchor-redefined", E, "an anchor name is defined twice",
       "Choreonoid refuses the file (Anchor is duplicated)", ""},
      {"yaml-undefined-alias", E, "an alias names no anchor", "Choreonoid refuses the file (Anchor is not defined)",
       ""},
      {"yaml-recursive-alias", F, "an alias refers to the node that contains it", "the document would be infinite", ""},
      {"yaml-merge-invalid", E, "a `<<` merge value is not a mapping or a list of mappings",
       "Choreonoid refuses the file", ""},
      {"yaml-empty-key", E, "a mapping key is empty", "Choreonoid refuses the file (empty key)", ""},
      {"yaml-complex-key", E, "a mapping key is not a scalar", "Choreonoid's reader only supports scalar keys", ""},
      {"yaml-alias-expansion", F, "alias expansion exceeds the node budget",
       "a \"billion laughs\" document would exhaust memory in any consumer",
       "LoadOptions::max_expanded_yaml_nodes (default 40,000,000)"},
      {"yaml-depth", F, "nesting exceeds the depth budget", "deep nesting exhausts the stack of recursive readers",
       "LoadOptions::max_yaml_depth (default 200)"},
      // Body header and keys (§2, §14)
      {"load-top-level", F, "the document is not a mapping", "a body file is a mapping of header keys", ""},
      {"load-format", F, "`format` is missing or not ChoreonoidBody", "Choreonoid refuses the file", ""},
      {"load-format-version", F, "`format_version` is missing or unsupported (>= 2.1)", "Choreonoid refuses the file",
       ""},
      {"load-angle-unit", F, "`angle_unit` is neither degree nor radian", "Choreonoid refuses the file", ""},
      {"load-wrapper", F,
       "a wrapper file's model (model_file without format) does not load, or its model_file or geometry value "
       "is malformed",
       "there is no model to check", ""},
      {"wrapper-format", F, "a wrapper file's model_file names a format bodyfmt does not read (or a URI)",
       "there is no model to check", "LoadOptions::model_file_readers (the tools read .urdf)"},
      {"wrapper-missing", F, "the model_file of a wrapper file cannot be read", "there is no model to check", ""},
      {"wrapper-recursion", F, "wrapper files include themselves or each other, or nest too deep",
       "loading would never end", ""},
      {"wrapper-link-info", W, "a wrapper's linkInfo names a link the model does not have",
       "Choreonoid silently ignores that info", ""},
      {"load-no-links", F, "no links are defined", "a body needs at least one link", ""},
      {"load-legacy-shininess", N, "the VRML-style material key shininess (0..1), converted to specular_exponent",
       "it loads as 127 * shininess + 1; specular_exponent is the format's own key", ""},
      {"load-legacy-key", W, "a legacy camelCase key or value",
       "it loads, but the modern snake_case spelling is the documented one", ""},
      {"fix-left-out", N,
       "bodycheck --fix left a fix-it (or the whole --upgrade) out: its edit is of text another use shares (an "
       "anchor, alias or merge), which it would change too; the rest of the file is fixed",
       "a fix-it must never change the model; the note names the difference the edit would make", ""},
      {"fix-geometry-unavailable", N,
       "bodycheck --fix=geometry has no tensor from the shapes for a link an inertia rule flags: it has no solid "
       "geometry, no link-level mass, or keys not written as plain numbers in place",
       "the link's mass properties must then be set by hand; the note says which of these it is", ""},
      {"load-format-upgrade", N, "a format 1.0 file; `bodycheck --fix --upgrade` rewrites it as format 2.0",
       "2.0 is snake_case keys and degrees only; converting radian values by hand is error-prone (per-key rules)", ""},
      {"load-unknown-key", W, "an unknown key close to a known one (probable typo)",
       "Choreonoid ignores it silently, so the intended value is lost",
       "edit distance <= 1 (the longer word 4-7 characters) or 2 (8+ characters), transpositions count once"},
      {"load-unknown-model-key", E,
       "an unknown key close to a key that changes the model (probable typo of mass, inertia, center_of_mass, "
       "translation, rotation, scale, parent, joint_type, joint_axis, joint_range, joint_angle, "
       "joint_displacement, max_joint_velocity, joint_velocity_range, max_joint_effort, joint_axis_inertia, "
       "rotor_inertia, gear_ratio, elements, geometry, size, radius, height)",
       "Choreonoid ignores it silently, so the model is loaded with the default value (a 1 kg link, a joint about Z, "
       "an unlimited joint)",
       "as load-unknown-key; snake_case and camelCase spellings are both candidates"},
      {"load-info-key", N, "a key the format does not define", "Choreonoid keeps it as info for other subsystems", ""},
      {"load-key-written-twice", W,
       "a key written in two of its spellings in one mapping (`jointType` beside `joint_type`, body-format-spec §14)",
       "Choreonoid reads the first spelling of its list (snake_case) and ignores the other, so one of the two values "
       "is silently lost",
       ""},
      {"load-misplaced-key", W,
       "a key written one level too deep where it means nothing: `appearance` under a Shape's `geometry`",
       "Choreonoid ignores it there, so the shape gets the default material; it belongs to the Shape node", ""},
      {"load-ignored-key", W, "a key Choreonoid reads under another name or not at all", "its value has no effect", ""},
      {"load-ignored-value", W, "a value Choreonoid ignores (wrong type for an optional key)",
       "the default is used instead, silently in Choreonoid", ""},
      {"load-lenient-number", W, "a number with trailing garbage, e.g. `0.t`",
       "Choreonoid reads the numeric prefix silently", ""},
      {"load-number", E, "a value must be a number", "Choreonoid refuses the file", ""},
      {"load-bool", E, "a value must be a boolean", "Choreonoid refuses the file", ""},
      {"load-type", E, "a value has the wrong YAML type", "Choreonoid refuses the file or ignores the node", ""},
      {"load-type-mismatch", E, "an inner `type` differs from the type key of a type-keyed mapping",
       "Choreonoid refuses the file", ""},
      {"load-missing-key", E, "a required key is missing", "Choreonoid refuses the file", ""},
      {"load-vector-size", E, "a vector has the wrong number of elements", "Choreonoid refuses the file", ""},
      {"load-rotation-axis", E, "a rotation axis is the zero vector", "Choreonoid refuses the file", ""},
      {"load-inertia-size", E, "an inertia has neither 6 nor 9 elements", "Choreonoid refuses the file", ""},
      {"load-axis", E, "an illegal joint axis symbol", "Choreonoid refuses the file", ""},
      {"load-range", E, "an invalid joint range or limit", "Choreonoid refuses the file", ""},
      {"load-infinite-limit", N, "a joint limit written as infinity (`inf`, or a number too large for a double)",
       "Choreonoid's strtod reads it as an open side, as `unlimited`; other YAML readers take the word as text", ""},
      {"load-joint-type", E, "an illegal joint type", "Choreonoid refuses the file", ""},
      {"load-actuation-mode", E, "an illegal actuation mode", "Choreonoid refuses the file", ""},
      {"load-angle-on-prismatic", W, "joint_angle on a prismatic joint in a degree file",
       "Choreonoid converts it from degrees", ""},
      {"load-link-name", W, "a link has no name",
       "Choreonoid loads it (a root or a leaf), but nothing can name it as a parent and URDF and MJCF cannot "
       "write it",
       ""},
      {"load-link-type", E, "an unknown node type in `links`", "Choreonoid refuses the file", ""},
      {"load-mass-ignored", W, "mass keys where Choreonoid ignores them (Transform, SubBody)",
       "the mass the author meant is not simulated", ""},
      {"load-default-mass", N, "a link has no mass data and gets 1 kg with identity inertia",
       "Choreonoid simulates these defaults; other engines differ", ""},
      {"load-import", N, "`import` only adds info keys", "model keys inside it have no effect", ""},
      {"load-scene-node", N, "a scene-only node (light, camera, fog) in a body", "it has no meaning for the body", ""},
      {"load-unknown-node-type", E, "an unknown element node type", "Choreonoid refuses the file", ""},
      {"load-optional-node-skipped", W, "an unknown element node type marked is_optional",
       "Choreonoid skips it, so whatever it was meant to add is missing", ""},
      {"load-plugin-node", W, "a node type that needs a Choreonoid plugin",
       "kept as an opaque device; Choreonoid refuses the file without the plugin", ""},
      {"load-visual-collision-conflict", E, "Visual inside Collision or the reverse", "Choreonoid refuses the file",
       ""},
      {"load-continuous-track", E, "an invalid ContinuousTrack node", "Choreonoid refuses the file", ""},
      {"load-track-name", W, "a link names a ContinuousTrack by the node's own name",
       "Choreonoid registers the name for the track's first link NAME0 too; no other reader knows it", ""},
      {"load-track-shared-joint", W, "the links of a ContinuousTrack share the node's joint_name or joint_id",
       "Choreonoid copies both into every link without a check; only the first link holds the id in the joint list",
       ""},
      {"load-uri", E, "a URI cannot be resolved (scheme, package or path variable)", "the resource cannot be loaded",
       ""},
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
      {"geometry-division-clamped", W, "a division_number above the tessellation limit is clamped",
       "a sphere has about n^2/2 vertices: a huge division number would exhaust memory", ""},
      {"geometry-more-problems", N, "further geometry problems of one shape are summarised, not listed",
       "one broken mesh would otherwise print thousands of lines", ""},
      {"geometry-invalid-size", E, "a non-positive size, radius or height", "Choreonoid refuses the shape", ""},
      {"geometry-degenerate", E, "an Extrusion, ElevationGrid or mesh that produces no valid surface",
       "Choreonoid crashes or drops the shape", ""},
      {"geometry-index-out-of-range", E, "a face index outside the vertex list", "Choreonoid refuses the file", ""},
      {"geometry-unterminated-polygon", W, "the last IndexedFaceSet polygon is not closed by -1",
       "Choreonoid silently drops it", ""},
      {"geometry-unknown-type", E, "an unknown geometry type", "Choreonoid refuses the file", ""},
      // Devices (§10)
      {"device-camera-dropped", W, "a Camera without a valid format", "Choreonoid silently drops the camera", ""},
      {"device-optical-frame", E, "an unknown optical frame", "Choreonoid refuses the file", ""},
      {"device-marker-type", E, "a MarkerDevice marker_type other than cross, sphere or axes",
       "Choreonoid refuses the file", ""},
      {"device-scaled-frame", W, "a device under a scaled node",
       "Choreonoid's device rotation includes the scale (not a rotation); bodyfmt keeps the pure rotation", ""},
      // Extra joints (§12)
      {"extra-joint-link", E, "an extra joint names no link", "Choreonoid refuses the file", ""},
      {"extra-joint-type", E, "an extra joint type is missing or unknown", "Choreonoid refuses the file", ""},
      {"extra-joint-axis", E, "an extra joint axis is the zero vector", "the joint has no direction", ""},
      // Resources (§9.1-9.4, §11.2)
      {"resource-missing", E, "a resource file cannot be read", "its geometry is missing", ""},
      {"resource-fragment", E, "a YAML fragment anchor is not found", "Choreonoid refuses the file", ""},
      {"resource-unsupported", E, "a Resource node where none can be read", "its geometry is missing", ""},
      {"resource-recursion", E,
       "YAML resources (with their fragments) include themselves or each other, or resources nested in one another "
       "are deeper than max_yaml_depth YAML levels together",
       "Choreonoid would recurse until its stack runs out", "LoadOptions::max_yaml_depth (default 200)"},
      // Scene files (.scen) named by a Resource node (§9.2)
      {"scene-header", E,
       "a scene file's header is malformed: not a mapping, format_version missing or >= 2.1, angle_unit neither "
       "degree nor radian (or radian in 2.0), or no `scene` key",
       "Choreonoid's scene loader loads nothing from the file, so the body refuses the resource", ""},
      {"scene-format-name", W, "a scene file's `format` is neither choreonoid_scene nor ChoreonoidScene",
       "Choreonoid does not check it, so a file meant as something else is read as a scene", ""},
      {"scene-empty", W, "a scene file's `scene` has no node", "the resource adds nothing to draw or collide", ""},
      {"scene-recursion", E,
       "scene files include themselves or each other, or nest deeper than 16 files or than max_yaml_depth YAML "
       "levels together",
       "loading would never end, or would run out of stack", "LoadOptions::max_yaml_depth (default 200)"},
      {"scene-expansion", E,
       "the scene files a body includes, counted once per use, expand to more YAML nodes than "
       "max_expanded_yaml_nodes",
       "files that each name another many times multiply: every use adds its shapes to the model",
       "LoadOptions::max_expanded_yaml_nodes (default 40,000,000)"},
      {"scene-unsupported", E,
       "a scene file resource bodyfmt or Choreonoid cannot read: a YAML resource inside a scene file, a "
       "node/fragment selecting part of a scene file, or a scene file given as a Shape's geometry that is not one "
       "shape without a transform of its own",
       "its shapes are missing", ""},
      {"subbody-missing", E, "a SubBody file cannot be read", "its links are missing", ""},
      {"subbody-load", E, "a SubBody file cannot be loaded", "its links are missing", ""},
      {"subbody-recursion", E, "SubBody includes form a cycle", "loading would never end", ""},
      {"mesh-file-missing", E, "a mesh file does not exist", "its geometry is missing", ""},
      {"mesh-file-unreadable", E, "a mesh file cannot be read", "its geometry is missing", ""},
      {"mesh-too-large", E,
       "a binary STL mesh holds more triangles than --max-mesh-triangles (default 1,000,000), so it is not imported",
       "an import takes about 1.5 KB per triangle: a 250 MiB file would take gigabytes before anything is checked", ""},
      {"mesh-format-unsupported", E, "a mesh file extension no reader supports", "its geometry is missing", ""},
      {"mesh-importer-unavailable", E, "the assimp import module (libbodyfmt_assimp.so) cannot be loaded",
       "STL, OBJ, COLLADA and glTF meshes are left out",
       "looked for next to libbodyfmt.so or the tool, then in the installed library folder"},
      {"mesh-parse", E, "a mesh file is malformed", "its geometry is missing or partial", ""},
      {"mesh-node-not-found", E, "the selected node is not in the mesh file", "Choreonoid refuses the file", ""},
      {"mesh-inline-cycle", E, "VRML Inline files include each other", "loading would never end", ""},
      {"mesh-reference-outside", E,
       "a mesh file names a file outside its own folder (an absolute path, a `..` out of it, a symbolic link "
       "leading out), such as a glTF buffer or an OBJ material library",
       "the mesh could copy any readable file (a key, a password file) into every export and the bodyview page; "
       "the mesh is not used",
       ""},
      {"mesh-texture-outside", W,
       "a mesh file names a texture outside its own folder (an absolute path, a `..` out of it, a symbolic link "
       "leading out)",
       "the exporters and bodyview would copy any readable file as the picture; the texture is not used, the mesh "
       "keeps its geometry",
       ""},
      {"mesh-vertex-not-finite", E, "a mesh file has a vertex or a node transform that is NaN or infinite",
       "no exporter can write it and no geometry can be computed from it; the mesh is not used", ""},
      {"mesh-invalid-geometry", E, "a mesh file has invalid geometry", "part of it is dropped", ""},
      {"mesh-empty", W, "a mesh file or node has no triangles", "nothing is drawn or collides", ""},
      // Validator rules (validate/rules/, bodycheck). Inertia: shared/spec/anchors.md §2.
      {"inertia-asymmetric", E, "a 9-element inertia is not symmetric",
       "Choreonoid uses the 9 numbers as given; engines assume a symmetric tensor and silently use a part of it",
       "|I - I^T|max > CheckOptions::inertia_symmetry_tolerance (1e-6) x |I|max, per RigidBody or link-level inertia"},
      {"derived-not-finite", E,
       "a link's combined mass properties or world frame overflow to infinity or NaN, or its combined inertia is too "
       "large to decompose",
       "every number written or simulated from it would be NaN; each input value was finite",
       "an infinite or NaN sum, or a combined inertia entry beyond 1e100 kg m^2"},
      {"suppression-unknown-rule", W, "a `# bodycheck: disable=` comment names no rule",
       "a mistyped id suppresses nothing, and the finding it was meant for still fails the run", ""},
      {"suppression-unused", W, "a `# bodycheck: disable=` comment suppresses nothing on the line it covers",
       "a stale suppression would silently hide a new finding on that line", ""},
      {"inertia-not-positive-definite", E, "the combined inertia of a link has a negative principal moment",
       "MuJoCo, Drake and gz-math refuse it; the dynamics are unphysical",
       "smallest eigenvalue < -16*DBL_EPSILON*max(1, trace/2) (Drake's); exactly < 0 for a diagonal tensor"},
      {"inertia-triangle", E, "the principal moments violate the triangle inequality (A + B < C)",
       "no rigid body has such moments; MuJoCo refuses any violation, Drake one beyond 16*eps*max(1, tr/2), gz-math "
       "one beyond 10*eps*tr/2; `bodycheck --fix=geometry` computes the tensor from the link's shapes",
       "A + B - C < 0 exactly for a diagonal tensor (MuJoCo); < -4*DBL_EPSILON*trace otherwise (eigen-solver "
       "rounding)"},
      {"inertia-nonpositive-mass", E, "a negative mass, or zero mass on a moving link",
       "MuJoCo clamps negative mass to 0 and refuses massless moving bodies; Drake and gz-math refuse negative mass",
       "moving = revolute, prismatic or free joint; zero mass passes when a fixed descendant carries mass (MuJoCo's "
       "rule)"},
      {"inertia-tiny", E, "a moving link's mass or smallest principal moment is below 1e-15",
       "MuJoCo refuses moving bodies below mjMINVAL",
       "mass or principal moment < 1e-15 (mjMINVAL), unless a fixed descendant has both above it"},
      {"inertia-com-outside", W, "the centre of mass lies outside the link's geometry bounds",
       "usually a wrong center_of_mass or a frame mix-up (e.g. world instead of link frame)",
       "only links that can move; outside the tight visual+collision box enlarged by 1% of its diagonal + 1 mm"},
      {"inertia-implausible", W,
       "the inertia is far from that of the link's geometry bounding box filled with its mass",
       "usually a placeholder, a unit error (g, mm) or an inertia about the wrong point",
       "only links that can move; trace ratio outside [1/f, f], f = CheckOptions::inertia_plausibility_factor (10)"},
      {"inertia-geometry-not-solid", W,
       "a shape whose mass properties are computed from the geometry is not a closed, consistently oriented solid",
       "a shell bounds no volume: the divergence theorem over it gives a meaningless mass, so the shape is left out",
       "only where mass is computed from the geometry (bodyinfo --mass-from-geometry, bodycheck --fix=geometry); "
       "edges compared by vertex position: each must be run as often forwards as backwards"},
      // Joints (body-format-spec §5.3, §6, §15)
      {"joint-id-duplicate", E, "two joints share a joint_id",
       "Choreonoid keeps one joint per id; controllers drive the wrong joint", ""},
      {"joint-id-gap", W, "joint ids skip numbers below the largest id",
       "Choreonoid warns and reserves an empty joint slot for each missing id", ""},
      {"joint-id-on-fixed", W, "a fixed joint has a joint_id", "the id occupies a controller slot that cannot move",
       ""},
      {"joint-axis-zero", E, "a revolute, prismatic or track joint axis is the zero vector",
       "the joint has no direction; MuJoCo refuses it (axis too small)", "|axis| < 1e-9"},
      {"joint-axis-not-unit", W, "a joint axis is not a unit vector",
       "Choreonoid does not normalise it, so joint velocities and displacements are scaled", "||axis| - 1| > 1e-6"},
      {"joint-range-reversed", E, "a joint range has lower > upper",
       "Choreonoid accepts it silently; MuJoCo's URDF import makes the joint unlimited", ""},
      {"joint-range-zero-width", W, "a joint range has lower == upper", "the joint cannot move; a fixed joint says so",
       ""},
      {"joint-velocity-negative", E, "a negative max_joint_velocity or a velocity range that excludes 0",
       "the joint cannot stand still within its velocity limits", ""},
      // Units (body-format-spec §3)
      {"units-range-looks-radian", W, "a revolute range in a degree file looks like radians",
       "format 2.0 angles are degrees: [-1.57, 1.57] is +-1.57 degrees",
       "finite limits all within 2pi+0.002 (as written), one non-zero, and either one within 0.002 of k*pi/12 (k = "
       "1..24) or all within pi+0.002 and none a whole number"},
      {"units-range-looks-degree", E, "a revolute range in a radian file (angle_unit: radian) looks like degrees",
       "[-90, 90] read in radians lets the joint turn 14 times each way; while it stands, the format upgrade (which "
       "would convert it as radians and make the mistake silent) is refused",
       "a finite limit beyond 2pi+0.002, none beyond 360 (as written), and every one beyond 2pi a multiple of 0.5; "
       "judged per file, in the file's own unit"},
      {"units-velocity-looks-degree", E,
       "a revolute velocity limit in a radian file (angle_unit: radian) looks like deg/s",
       "max_joint_velocity: 180 read in rad/s lets the joint turn 29 times a second; while it stands, the format "
       "upgrade is refused",
       "a finite limit beyond 16pi rad/s (8 turns a second), none beyond 3600 (as written), and every one beyond "
       "16pi a multiple of 0.5; judged per file, in the file's own unit"},
      {"units-rotation-looks-radian", W, "a rotation angle in a degree file looks like radians",
       "format 2.0 angles are degrees: rotation: [0, 0, 1, 1.5708] turns by 1.5708 degrees, not a quarter turn",
       "non-zero, within 2pi+0.002 and within 0.002 of k*pi/12 (k = 1..24), as written: the first test of "
       "units-range-looks-radian (a single small tilt, 2.35 degrees, is too common for its second)"},
      {"units-prismatic-millimetres", W, "a prismatic range beyond 10 m",
       "prismatic ranges are metres; millimetres make the limit 1000x too wide", "|limit| > 10 m"},
      {"units-mesh-millimetres", W, "a mesh in metres that is far too large for its link",
       "meshes exported in millimetres are 1000x too large",
       "largest extent > 100x the link's other geometry, or > 10 m on a moving link; only meshes without metadata "
       "length_unit"},
      // Structure, geometry, resources, devices
      {"structure-duplicate-device", W, "two named devices share a name",
       "Choreonoid and controllers look devices up by name and find only the first",
       "unnamed devices are not compared; reported whatever the device types"},
      {"geometry-zero-size", W, "a Box with a zero edge, or a shape scaled to zero",
       "Choreonoid allows it, but it has no volume: MuJoCo refuses zero sizes, collision engines degenerate", ""},
      {"resource-absolute-path", W, "a resource URI is an absolute path",
       "the model only works on the machine it was written on", ""},
      {"resource-case-mismatch", E, "a resource path matches a file on disk only with different letter case",
       "it loads on case-insensitive file systems (Windows, macOS) but not on Linux", ""},
      {"device-fov", E, "a camera field of view outside (0, 180) degrees (fisheye lenses: (0, 360])",
       "a perspective projection needs 0 < fov < 180 degrees", ""},
      {"device-resolution", E, "a non-positive camera resolution or range-sensor step", "the sensor produces no data",
       ""},
      {"device-clip", E, "near clip <= 0 or >= far clip (or min distance >= max distance)",
       "the depth range is empty or the projection is singular", ""},
      {"device-light", W, "light parameters out of range",
       "negative intensity or attenuation, colours outside [0, 1] or a spot cut-off outside (0, 180] degrees render "
       "wrongly",
       ""},
      // Exporters (converters/, each target's SUPPORT.md)
      {"export-loss", W, "the target format cannot express a construct of the model",
       "the exported file silently differs from what Choreonoid simulates unless this is reported", ""},
      {"export-link-unnamed", E, "a link without a name, which URDF and MJCF cannot write",
       "their joints, parents and contact exclusions refer to links by name; none is made up", ""},
      {"export-name", W, "a name the target format's tools cannot use, or one renamed to stay unique",
       "ROS tools (tf, MoveIt) rely on URDF names of letters, digits and '_'", ""},
      {"export-name-conflict", F,
       "a name the export must add is already used by the model (e.g. --floating-base's 'world')",
       "two elements of one name make the output ambiguous, so nothing is written", ""},
      {"export-range-reversed", W,
       "a joint range with lower > upper written as it is (URDF), as urdfdom and Choreonoid keep it",
       "a URDF consumer may read the joint as unlimited (MuJoCo does) or as unable to move; bodycheck reports the "
       "range itself as joint-range-reversed",
       ""},
      {"export-value-changed", W,
       "the export wrote a value other than the model's (a symmetrised or balanced inertia, a normalised joint axis, a "
       "raised mass, a widened empty range), at the value's line, with the value read, the value written and why",
       "the exported body simulates differently from the model as written unless this is reported; --strict makes it "
       "an error, as it does export-loss, and nothing is written",
       ""},
      {"appearance-value-range", W,
       "a material colour component or transparency is outside 0..1; Choreonoid keeps it and its renderer clamps it",
       "exporters must write the clamped value (MuJoCo refuses a colour of 4e68), and the author likely mistyped it",
       ""},
      // Importers (converters/FORMAT, each reader's IMPORT.md)
      {"import-syntax", F, "the input is not well-formed XML, or its document element is not <robot>",
       "nothing can be imported from it", ""},
      {"import-structure", E,
       "the URDF is not one tree: a joint names a missing link, a second root, a cycle, a link with two parent "
       "joints, a duplicate name, or a required element or attribute is missing",
       "urdfdom refuses such a file, and a body needs one tree", ""},
      {"import-value", E,
       "a URDF value does not read: not a finite number, a wrong count, an unknown joint type, a "
       "zero joint axis",
       "the imported model would hold a value the author did not write", ""},
      {"import-mass", E, "a negative mass or moment of inertia in a URDF <inertial>",
       "no physical body has one; simulators refuse or explode on it", ""},
      {"import-mesh", E, "a URDF mesh file cannot be found (the URI and every place searched are listed)",
       "the body would refer to a file that does not exist", ""},
      {"import-material", W, "a URDF visual names a material that is not defined",
       "the shape is imported without colour", ""},
      {"import-unknown-element", W, "an element URDF does not define (an extension of another tool)",
       "its content is not imported", ""},
      {"import-convention", W,
       "a URDF construct outside the URDF spec that ROS tools or simulators accept (missing products of "
       "inertia, a second shape in a <geometry>, lower > upper, a zero radius, <capsule>, a vector with commas); "
       "read as they do",
       "another consumer of the same file may read it differently or refuse it", ""},
      {"import-choreonoid-differs", N,
       "urdf2body wrote the URDF meaning of a construct that Choreonoid's URDF loader reads differently: a link "
       "without <inertial> is massless here and 1 kg with identity inertia there; a root `world` link is the fixed "
       "frame here and a free-floating link there (converters/urdf/IMPORT.md, \"Two readings\")",
       "a wrapper body file around the same URDF loads as Choreonoid reads it, so the two models differ there", ""},
      {"wrapper-urdf-mass", W,
       "a link of a wrapper body file's URDF has no <inertial>, or an <inertial> no <inertia>: Choreonoid's URDF "
       "loader gives it 1 kg at its origin with identity inertia (identity inertia), where URDF means a massless "
       "frame; the model is loaded so",
       "a wrapper is a Body file: Choreonoid simulates phantom masses the URDF's author did not write (each link "
       "without <inertial> adds 1 kg)",
       ""},
      {"wrapper-urdf-world", W,
       "a wrapper body file's URDF has a root link named `world` on a fixed or floating joint: Choreonoid's URDF "
       "loader keeps it as a link, the body's free-floating root, so the robot is not fixed to the ground",
       "ROS tools take `world` as the fixed frame; in Choreonoid the base falls or drifts (urdf2body's .body fixes it)",
       ""},
      {"wrapper-urdf-semantics", W,
       "a wrapper body file's URDF says something else Choreonoid's URDF loader reads differently from the URDF "
       "spec: a floating, planar or unknown joint type (fixed), a negative box edge or a sphere or cylinder size "
       "that is not positive (no shape); the model is loaded as Choreonoid loads it",
       "a wrapper is a Body file: Choreonoid simulates it so, which the URDF's author most likely did not mean", ""},
      {"wrapper-urdf-refused", E,
       "a wrapper body file's URDF holds what Choreonoid's URDF loader refuses: a mass of 0, a <limit> without "
       "velocity or effort or with a negative one, an <inertia> without a product of inertia, an <axis> without xyz, "
       "a second shape in a <geometry>, <capsule>",
       "Choreonoid loads no body from the wrapper; bodyfmt reads on to report the rest", ""},
      // Dynamics checker (dynamics/, bodysim)
      {"dynamics-contact-geometry", W,
       "bodysim --contact simbody could not turn a collision shape into Simbody contact geometry (a Brick needs a "
       "rigid placement, a TriangleMesh a closed surface), so that shape does not touch the floor",
       "a shape without floor contact changes the simulation; it must not vanish silently", ""},
      {"dynamics-engine-failure", F,
       "Simbody or MuJoCo stopped with an exception while bodysim simulated the model; reported at the part of the "
       "model most likely to cause it (the stiffest contact, servo or inertia), with the engine's message",
       "an engine's exception names no link; the user needs the line of the model to look at", ""},
      {"dynamics-inertia-balanced", W,
       "bodysim --balance-inertia simulated a link with the balanced tensor instead of its unphysical inertia, with "
       "the old and new values",
       "the simulated body differs from the model as written unless this is reported", ""},
      {"dynamics-model-size", F,
       "bodysim was given a model with more links than --max-links (default 200): Simbody's integration time grows "
       "faster than the link count (100 links took 8 s, 300 links 35 s), so it stops before the work",
       "a checker that runs for hours on a generated model is a hang; the limit says so and can be raised", ""},
      {"dynamics-scenario", E,
       "a bodysim scenario file is malformed (syntax, unknown key, bad value or link name), has a negative servo "
       "gain, or asks for more than bodysim's limits (--max-duration, --max-rows, --max-commands)",
       "nothing is simulated from a scenario that cannot be read as written, or that would not finish", ""},
      {"dynamics-work-budget", F,
       "a bodysim simulation spent its work budget (--max-steps-per-second, --max-cpu) and was stopped, with the "
       "stiffest part of the model as the likely cause",
       "an explicit integrator on a stiff contact or servo crawls for hours; a hang must be a located error", ""},
      {"export-xml-text", F,
       "a name or text that XML cannot hold (control characters, non-characters or invalid UTF-8)",
       "no XML parser would read the output, so nothing is written", ""},
      {"export-write", F, "an output file cannot be written or encoded",
       "nothing is written, so no output is left half-written", ""},
  };
  // Fix-its (Diagnostic::fixes) and how far `bodycheck --fix` may apply them.
  const std::vector<std::pair<std::string_view, std::string_view>> fixes = {
      {"load-legacy-key", "safe: the snake_case spelling (key or joint type value)"},
      {"load-format-upgrade", "upgrade: format_version 2.0, angle_unit degree, radian values in degrees (spec §3)"},
      {"load-unknown-key", "unsafe: the did-you-mean key (the value is then read, so the model changes)"},
      {"load-unknown-model-key", "unsafe: the did-you-mean key (the value is then read, so the model changes)"},
      {"load-key-written-twice",
       "unsafe: removes the lines of the ignored spelling (where a value does not convert, Choreonoid's Mapping::read "
       "goes on to the next spelling, so the model may change)"},
      {"load-misplaced-key",
       "unsafe: moves the lines one level up, when the key is the last of geometry and the Shape has no appearance "
       "(the material is then read, so the model changes)"},
      {"structure-unknown-parent", "unsafe: the nearest link name, when one is nearest (the link is then attached)"},
      {"units-range-looks-degree", "unsafe: reinterpret as degrees (the radians they stand for are written)"},
      {"units-velocity-looks-degree", "unsafe: reinterpret as deg/s (the rad/s it stands for is written)"},
      {"units-rotation-looks-radian", "unsafe: reinterpret as radians (the degrees it stands for are written)"},
  };
  for (RuleInfo& rule : rules)
    for (const auto& [id, fix] : fixes)
      if (rule.id == id) rule.fix = fix;
  std::sort(rules.begin(), rules.end(), [](const RuleInfo& a, const RuleInfo& b) { return a.id < b.id; });
  return rules;
}

}  // namespace

const std::vector<RuleInfo>& all_rules() {
  static const std::vector<RuleInfo> rules = make_table();
  return rules;
}

Diagnostic make_diagnostic(std::string_view rule_id, SourceLocation location, std::string message,
                           std::string fix_hint) {
  const RuleInfo* rule = find_rule(rule_id);
  Diagnostic d;
  d.severity = rule ? rule->default_severity : Severity::kError;
  d.rule_id = std::string(rule_id);
  d.message = std::move(message);
  d.location = std::move(location);
  d.fix_hint = std::move(fix_hint);
  return d;
}

void report_rule(DiagnosticSink& sink, std::string_view rule_id, SourceLocation location, std::string message,
                 std::string fix_hint) {
  sink.report(make_diagnostic(rule_id, std::move(location), std::move(message), std::move(fix_hint)));
}

const RuleInfo* find_rule(std::string_view id) {
  const auto& rules = all_rules();
  auto it = std::lower_bound(rules.begin(), rules.end(), id,
                             [](const RuleInfo& r, std::string_view key) { return r.id < key; });
  return it != rules.end() && it->id == id ? &*it : nullptr;
}

}  // namespace bodyfmt
