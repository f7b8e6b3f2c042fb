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
  /// Contacts between the model's own bodies. Off (Choreonoid's default: BodyItem's
  /// self-collision detection is off): no two bodies of the model touch each other, by
  /// <exclude> pairs for a model with at most kMaxExcludeBodies colliding bodies, by contact
  /// bits otherwise. On: MuJoCo's own rule (only a body and its parent never touch).
  bool self_collision = false;
  /// The contact bit (1 .. kMaxCollisionGroup) that keeps the model's bodies apart: collision
  /// geoms get contype = 2^group and conaffinity = every other bit, so they touch a default
  /// geom (contype = conaffinity = 1) and every geom of another group, but not each other nor
  /// another export with the same group. 0: automatic (excludes for a small model, else the
  /// group derived from the model name, collision_group_of).
  int collision_group = 0;
};

/// Up to this many bodies with collision geoms, self-collision is switched off with one
/// <exclude> per pair (at most 2,016), which leaves the contact bits as MuJoCo's defaults.
constexpr std::size_t kMaxExcludeBodies = 64;
/// The highest contact bit a group may use: conaffinity keeps the other bits of a 31-bit
/// positive int.
constexpr int kMaxCollisionGroup = 30;
/// The automatic group of a model too large for excludes: 1 + FNV-1a(name) mod 30, so two
/// different models rarely share one.
int collision_group_of(const std::string& model_name);

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
