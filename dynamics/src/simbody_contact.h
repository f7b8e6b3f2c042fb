#pragma once
// `--contact simbody`: floor contact through Simbody's own contact stack (ContactTrackerSubsystem +
// CompliantContactSubsystem) instead of the point-contact force. A HalfSpace on Ground is the
// floor z = 0; Box collision shapes become Bricks (BrickHalfSpacePenalty: the 4 vertices of the
// face towards the floor), every other collision shape a closed TriangleMesh from the shared
// tessellator, refined so that Simbody's elastic foundation (one spring per face centroid) samples
// a flat face. Both generators are wrapped to add the belt surface velocity of pseudo tracks
// (dynamics-checker.md §2.3 Option B). Private to dynamics/: only simulation.cpp uses it.

#include <bodyfmt/dynamics/simulation.h>

#include <Simbody.h>

#include <memory>
#include <vector>

namespace bodyfmt::dynamics {

/// What the force generators read besides Simbody's State (owned by the Simulation).
struct BeltInputs {
  const std::vector<double>* track_speed = nullptr;          // by link, m/s (set_track_speed)
  const std::vector<Eigen::Vector3d>* track_axis = nullptr;  // by link, link frame, unit; zero if not a track
};

class SimbodyContact {
 public:
  /// Adds the floor and every collision shape of `model` to `system`. `mobod` maps links to
  /// mobilized bodies. `springs` receives where the model touches the floor: a Brick's 8
  /// corners and every elastic-foundation spring (face centroid of the refined mesh), in their
  /// link's frame. Shapes that cannot become Simbody contact geometry are reported
  /// (dynamics-contact-geometry) and left out.
  static std::unique_ptr<SimbodyContact> build(SimTK::MultibodySystem& system, SimTK::SimbodyMatterSubsystem& matter,
                                               const Model& model, const std::vector<SimTK::MobilizedBodyIndex>& mobod,
                                               const ContactParams& params, double weight, BeltInputs belt,
                                               DiagnosticSink& sink, std::vector<ContactPoint>& springs);

  /// Sum of the contact forces on `link` (or on the whole model: -1), world axes; `state` realized
  /// to Velocity.
  Eigen::Vector3d total_force(const SimTK::State& state, LinkIndex link) const;
  double brick_stiffness() const { return brick_stiffness_; }  ///< N/m per Brick vertex
  double mesh_stiffness() const { return mesh_stiffness_; }    ///< N/m³ (pressure per depth)
  int bricks() const { return bricks_; }
  int meshes() const { return meshes_; }
  int mesh_faces() const { return mesh_faces_; }

 private:
  SimTK::ContactTrackerSubsystem* tracker_ = nullptr;
  SimTK::CompliantContactSubsystem* contact_ = nullptr;
  std::vector<LinkIndex> link_of_mobod_;  // by MobilizedBodyIndex; -1 for Ground
  double brick_stiffness_ = 0, mesh_stiffness_ = 0;
  int bricks_ = 0, meshes_ = 0, mesh_faces_ = 0;
};

}  // namespace bodyfmt::dynamics
