#pragma once
/// Reporting what a target format cannot express (rule `export-loss`, a warning by default;
/// a DiagnosticPolicy with `strict` makes it an error). Every loss has a kind, carried as the
/// diagnostic's category, so that `--allow-loss KIND,...` can accept the known ones.
#include <bodyfmt/diagnostic.h>

#include <optional>
#include <string>
#include <string_view>

namespace bodyfmt::converters {

enum class LossKind {
  kTracks,       ///< a track's belt motion
  kExtraJoints,  ///< closed loops and other extra joints
  kDevices,      ///< sensors, cameras and lights, or some of their parameters
  kTextures,     ///< texture images
  kMaterials,    ///< material terms the target has no place for
  kGeometry,     ///< shapes or shape details
  kJoints,       ///< joint types, ranges and limits
  kDynamics,     ///< rotor inertia, contact material, actuation mode, initial pose
};

/// "tracks", "closed-loops", "devices", "textures", "materials", "geometry", "joints", "dynamics".
std::string_view loss_kind_name(LossKind kind);
std::optional<LossKind> parse_loss_kind(std::string_view name);
/// Every kind name, comma-separated, for usage messages and --help.
std::string loss_kind_names();

/// Reports `export-loss` at `location` (the element's source line):
/// "<target> cannot express <what>", with `hint` as the fix hint and the kind as category.
void report_loss(DiagnosticSink& sink, const SourceLocation& location, std::string_view target, LossKind kind,
                 std::string_view what, std::string_view hint = {});

}  // namespace bodyfmt::converters
