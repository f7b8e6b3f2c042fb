#pragma once
/// body2mjcf's writer: Model -> MJCF for MuJoCo 2.2.2 (see SUPPORT.md for what maps, what is
/// approximated and what is lost; every lost construct is reported as `export-loss` at its
/// source line and noted in an XML comment in the output).
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <string>

namespace bodyfmt::mjcf {

enum class Actuators { kNone, kPosition, kVelocity };

struct MjcfOptions {
  /// Write the nearest valid tensor (bodyfmt::balance_inertia) for links whose inertia MuJoCo
  /// refuses, with a warning per link; without it such a model is refused (inertia-triangle).
  bool balance_inertia = false;
  /// One actuator per revolute and prismatic joint, in joint-id order.
  Actuators actuators = Actuators::kNone;
  /// Folder for written meshes, relative to the MJCF file (the compiler's meshdir). Empty: the
  /// per-export default (assets/STEM, STEM the output file's stem).
  std::string mesh_folder;
};

/// The smallest mass and principal moment written for a moving link whose own values MuJoCo
/// refuses (below mjMINVAL = 1e-15) and that has no welded descendant carrying mass.
constexpr double kMinMovingMass = 1e-6;     // kg
constexpr double kMinMovingInertia = 1e-9;  // kg·m²

/// Builds the MJCF document and its mesh files and stages them in `output`. Losses go to
/// `sink` as `export-loss`; an inertia MuJoCo refuses (without balance_inertia) is reported as
/// `inertia-triangle` / `inertia-not-positive-definite` (errors) and a problem that makes the
/// output unusable (a name XML cannot hold, a mesh that cannot be encoded) as fatal; in both
/// cases output.fail() is called and false returned.
bool write_mjcf(const Model& model, const Derived& derived, const MjcfOptions& options, converters::OutputSet& output,
                DiagnosticSink& sink);

}  // namespace bodyfmt::mjcf
