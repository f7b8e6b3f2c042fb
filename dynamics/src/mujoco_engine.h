#pragma once
// The two engines of the MuJoCo cross-checks behind one interface: Simbody (a Simulation) and
// MuJoCo 2.2.2 running body2mjcf's export of the same model with a floor added by an include
// scene. Private to the cross-check target (bodyfmt_mujoco_cross_check).

#include <bodyfmt/dynamics/simulation.h>

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bodyfmt::dynamics {

/// What the scenarios need from an engine.
class Engine {
 public:
  virtual ~Engine() = default;
  virtual void drive(LinkIndex track, double dq) = 0;
  virtual void servo(LinkIndex joint, double p_gain, double d_gain, double q_ref) = 0;
  virtual void advance_to(double t) = 0;
  virtual double time() const = 0;
  /// Root velocity along its own heading: forward, lateral, and the world yaw rate.
  virtual Eigen::Vector3d heading_velocity() const = 0;
  virtual double joint_position(LinkIndex joint) const = 0;
  virtual double root_height() const = 0;
  virtual double floor_force() const = 0;
  virtual Eigen::Isometry3d root_pose() const = 0;
  virtual double kinetic_energy() const = 0;
  /// Deepest penetration into the floor (m) and the number of points that carry the model.
  virtual double penetration() const = 0;
  virtual int contacts() const = 0;
};

class SimbodyEngine : public Engine {
 public:
  SimbodyEngine(std::unique_ptr<Simulation> sim, double z);
  SimbodyEngine(std::unique_ptr<Simulation> sim, const Eigen::Isometry3d& root);
  void drive(LinkIndex track, double dq) override;
  void servo(LinkIndex joint, double p, double d, double q_ref) override;
  void advance_to(double t) override;
  double time() const override;
  Eigen::Vector3d heading_velocity() const override;
  double joint_position(LinkIndex joint) const override;
  double root_height() const override;
  double floor_force() const override;
  Eigen::Isometry3d root_pose() const override;
  double kinetic_energy() const override;
  double penetration() const override;
  int contacts() const override;

 private:
  std::unique_ptr<Simulation> sim_;
};

/// MuJoCo on a compiled export. Installs mjcb_control while it lives: one engine at a time per
/// process (spec §6.8).
class MujocoEngine : public Engine {
 public:
  /// The root at height z, the rest of its pose as the export wrote it.
  MujocoEngine(const Model& model, mjModel* m, double z);
  MujocoEngine(const Model& model, mjModel* m, const Eigen::Isometry3d& root);
  ~MujocoEngine() override;
  MujocoEngine(const MujocoEngine&) = delete;
  MujocoEngine& operator=(const MujocoEngine&) = delete;
  void drive(LinkIndex track, double dq) override;
  void servo(LinkIndex joint, double p, double d, double q_ref) override;
  void advance_to(double t) override;
  double time() const override;
  Eigen::Vector3d heading_velocity() const override;
  double joint_position(LinkIndex joint) const override;
  double root_height() const override;
  double floor_force() const override;
  Eigen::Isometry3d root_pose() const override;
  double kinetic_energy() const override;
  double penetration() const override;
  int contacts() const override;

 private:
  void bind();
  struct Servo {
    double p, d, q_ref;
    bool on;
  };
  static void control(const mjModel* m, mjData* d);

  const Model& model_;
  mjModel* m_;
  mjData* d_;
  std::vector<double> track_speed_;
  std::vector<Servo> servo_;
  std::vector<int> body_, joint_;
};

/// Changes the written export (its path given) before MuJoCo compiles it; false, with why, to stop.
using ExportEdit = std::function<bool(const std::filesystem::path& mjcf, std::string& why)>;

/// Exports `model` with body2mjcf's writer (the `balance_inertia` policy of `options`) into a
/// scratch folder, adds the floor plane "bodysim_floor" through an <include> scene, and compiles
/// it. Errors of the export are reported to `sink`; on failure returns null and says why.
mjModel* load_mujoco_export(const Model& model, const Derived& derived, const SimOptions& options, DiagnosticSink& sink,
                            std::string& why, const ExportEdit& edit = {});

}  // namespace bodyfmt::dynamics
