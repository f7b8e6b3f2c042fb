// Generic physics checks for any model (dynamics-checker.md §4 "Generic checks"): G2 mass
// matrix at random poses, G5 drop and settle.

#include <bodyfmt/dynamics/checks.h>

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>

namespace bodyfmt::dynamics {
namespace {

constexpr double kPi = 3.14159265358979323846;

CheckResult make(std::string name, double measured, double expected, std::string unit, std::string tolerance,
                 bool passed) {
  return {std::move(name), measured, expected, std::move(unit), std::move(tolerance), passed};
}

}  // namespace

std::vector<CheckResult> run_generic_checks(const Model& model, const Derived& derived, const SimOptions& options,
                                            DiagnosticSink& sink, std::string& why) {
  std::vector<CheckResult> results;
  std::unique_ptr<Simulation> sim = Simulation::build(model, derived, options, sink);
  if (!sim) {
    why = "the model cannot be simulated as written (see above)";
    return results;
  }
  CollectingSink quiet;

  // G2: the mass matrix is symmetric and positive definite at random poses inside the ranges.
  {
    std::mt19937 random(12);  // fixed seed: the same poses every run
    double worst_asymmetry = 0, worst_ratio = std::numeric_limits<double>::infinity(), worst_condition = 0;
    bool cholesky = true;
    const int poses = 20;
    int size = 0;
    for (int pose = 0; pose < poses; ++pose) {
      std::vector<double> q(model.links.size(), 0.0);
      for (std::size_t i = 0; i < model.links.size(); ++i) {
        const Link& link = model.links[i];
        if (!sim->has_joint(static_cast<LinkIndex>(i))) continue;
        const double span = link.joint_type == JointType::kRevolute ? kPi : 1.0;
        const double lo = std::max(link.joint_range_lower, -span), hi = std::min(link.joint_range_upper, span);
        q[i] = lo <= hi ? std::uniform_real_distribution<double>(lo, hi)(random) : 0.0;
      }
      const Eigen::MatrixXd M = sim->mass_matrix_at(q);
      size = static_cast<int>(M.rows());
      if (M.size() == 0) break;
      const double scale = M.cwiseAbs().maxCoeff();
      worst_asymmetry = std::max(worst_asymmetry, (M - M.transpose()).cwiseAbs().maxCoeff() / scale);
      cholesky = cholesky && Eigen::LLT<Eigen::MatrixXd>(M).info() == Eigen::Success;
      const Eigen::VectorXd eigen = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
      worst_ratio = std::min(worst_ratio, eigen.minCoeff() / eigen.maxCoeff());
      worst_condition = std::max(worst_condition, eigen.maxCoeff() / eigen.minCoeff());
    }
    if (size > 0) {
      results.push_back(make(fmt::format("mass matrix ({0}×{0}) symmetric at {1} random poses", size, poses),
                             worst_asymmetry, 0, "rel", "≤ 1e-12", worst_asymmetry <= 1e-12));
      results.push_back(
          make(fmt::format("mass matrix positive definite (Cholesky; worst condition number {:.3g})", worst_condition),
               worst_ratio, 0, "λmin/λmax", "> 0", cholesky && worst_ratio > 0));
    }
  }

  // G5: drop from 2 cm onto the floor. Passive, the joints free: nothing diverges and the
  // energy never grows. With the joints locked at their initial positions (a passive robot
  // folds up or topples, which is not a model defect): the body comes to rest on its collision
  // geometry, carried by the floor.
  if (model.root().joint_type != JointType::kFree) return results;
  if (sim->contact_points().empty()) {
    why = "the model has no collision geometry to drop";
    return results;
  }
  for (const bool locked : {false, true}) {
    SimOptions drop_options = options;
    drop_options.lock_joints = locked;
    sim = Simulation::build(model, derived, drop_options, quiet);
    if (!sim) break;
    double lowest = std::numeric_limits<double>::infinity();
    BoundingBox box;
    for (const ContactPoint& p : sim->contact_points()) {
      const Eigen::Vector3d x = as_isometry(derived.X_WL[p.link]) * p.position_in_link;
      lowest = std::min(lowest, x.z() - p.radius);
      box.add(x - Eigen::Vector3d(0, 0, p.radius));
      box.add(x + Eigen::Vector3d(0, 0, p.radius));
    }
    const double drop = 0.02;
    Eigen::Isometry3d X = as_isometry(model.root().X_PL);
    X.translation().z() += drop - lowest;
    sim->set_root_pose(X);
    const double mass = derived.total_mass;
    const double height = std::max(box.max.z() - box.min.z(), 1e-3);
    const double e0 = sim->energy();
    double gain = 0;
    bool finite = true;
    const Eigen::Vector3d start = sim->link_pose(0).translation();
    const double duration = 3.0;
    std::string failure;
    try {
      for (int i = 1; i <= static_cast<int>(duration / 0.005); ++i) {
        sim->advance_to(0.005 * i);
        if (!sim->finite()) {
          finite = false;
          break;
        }
        gain = std::max(gain, sim->energy() - e0);
      }
    } catch (const WorkBudgetExceeded&) {
      throw;  // not a check that failed: the run stops, located at the cause
    } catch (const std::exception& e) {
      finite = false;
      failure = e.what();
    }
    const std::string label = locked ? "drop 2 cm, joints locked" : "drop 2 cm, joints free";
    results.push_back(make(label + ": state stays finite" + (failure.empty() ? "" : " (" + failure + ")"),
                           finite ? 1 : 0, 1, "", "= 1", finite));
    if (!finite) continue;
    if (!locked) {
      // Energy never grows while passive, beyond integration error: 1e-4 of the drop energy.
      const double drop_energy = mass * options.gravity * drop;
      results.push_back(make(label + ": energy gain max(E - E0)", gain, 1e-4 * drop_energy, "J", "≤ 1e-4·m·g·h",
                             gain <= 1e-4 * drop_energy));
      continue;
    }
    const double ke = sim->kinetic_energy();
    const double settle = 1e-4 * mass * options.gravity * height;
    results.push_back(make(fmt::format("{}: kinetic energy at {:g} s", label, duration), ke, settle, "J",
                           "≤ 1e-4·m·g·h_bbox", ke <= settle));
    const double depth = sim->max_penetration();
    results.push_back(
        make(label + ": penetration at rest", depth * 1e3, 2, "mm", "(0, 2] mm", depth > 0 && depth <= 2e-3));
    const double fz = sim->total_contact_force().z();
    results.push_back(make(label + ": floor force at rest = m·g", fz, mass * options.gravity, "N", "±1 %",
                           std::abs(fz - mass * options.gravity) <= 0.01 * mass * options.gravity));
    const Eigen::Vector3d moved = sim->link_pose(0).translation() - start;
    const double drift = std::hypot(moved.x(), moved.y());
    results.push_back(make(label + ": horizontal drift of the root", drift * 1e3, 10, "mm", "≤ 10 mm", drift <= 0.01));
  }
  return results;
}

}  // namespace bodyfmt::dynamics
