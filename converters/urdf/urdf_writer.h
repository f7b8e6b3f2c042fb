#pragma once
/// body2urdf's writer: Model -> URDF (see SUPPORT.md for what maps, what is approximated and
/// what is lost; every lost construct is reported as `export-loss` at its source line and
/// noted in an XML comment in the output).
#include <bodyfmt/converters/mesh_writer.h>
#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <filesystem>
#include <string>

namespace bodyfmt::urdf {

/// Unlimited effort, velocity and one-sided ranges are written as this stand-in.
using converters::kUnlimitedStandIn;

struct UrdfOptions {
  converters::MeshFormat mesh_format = converters::MeshFormat::kStl;
  /// Copy external mesh files next to the URDF instead of referencing them where they are.
  bool copy_meshes = false;
  /// "package://NAME/" prefix for mesh URIs (implies copying); empty = URIs relative to the
  /// URDF file.
  std::string package_uri;
  /// The folder of the package (its package.xml): package URIs are relative to it, and mesh
  /// folders may lie anywhere inside it. Empty: relative to the URDF's folder.
  std::filesystem::path package_root;
  /// Writes `<mujoco><compiler strippath="false"/></mujoco>` so that MuJoCo keeps the folders
  /// of mesh paths (it strips them by default, and then finds no mesh in a subfolder).
  bool mujoco_compiler = true;
  /// Folder for written meshes, relative to the URDF file. Empty: the
  /// per-export default (meshes/STEM, STEM the output file's stem).
  std::string mesh_folder;
  /// Adds a `world` link joined to the root by a floating joint (a fixed joint for a fixed
  /// root) placed at the root's initial pose.
  bool floating_base = false;
  /// Writes a Capsule as `<capsule radius length>` (along Z, length the straight part), which
  /// Drake and sdformat read but urdfdom refuses; without it a capsule is a tessellated mesh.
  bool capsules = false;
  /// Writes each device as a child link on a fixed joint instead of reporting it.
  bool devices_as_frames = false;
  /// Writes the nearest valid tensor (bodyfmt::balance_inertia, the tensor body2mjcf writes)
  /// for links whose inertia Drake, gz-math and MuJoCo refuse, reported as
  /// export-value-changed; without it such a tensor is written as given and reported as
  /// export-loss.
  bool balance_inertia = false;
};

/// Builds the URDF document and its mesh files and stages them in `output`. Losses go to
/// `sink` as `export-loss` (an inertia URDF consumers refuse among them); a problem that makes the output unusable (a
/// name XML cannot hold, a mesh that cannot be encoded, a `world` link clash) is reported as fatal and calls
/// output.fail(). Returns false in that case.
bool write_urdf(const Model& model, const Derived& derived, const UrdfOptions& options, converters::OutputSet& output,
                DiagnosticSink& sink);

}  // namespace bodyfmt::urdf
