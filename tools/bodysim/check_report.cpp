#include "check_report.h"

#include "report_lines.h"

#include <fmt/format.h>

#include <iostream>

namespace bodyfmt::tools {

void print_check_header(const SimCommand& command, const std::string& path, const Model& model, const Derived& derived,
                        const dynamics::TankLayout& tank) {
  const dynamics::TankSuiteOptions& suite = command.suite;
  const dynamics::SimOptions& sim = suite.sim;
  std::cout << wrap(
      fmt::format("bodysim {}: {} ({}), total mass {} kg", command.name, model.name, path, number(derived.total_mass)),
      2);
  std::cout << wrap(
      fmt::format("  Simbody 3.7, Runge-Kutta-Merson accuracy {:g}; floor contact {}, friction {:g}, "
                  "dissipation {:g} s/m, transition {:g} m/s; joint ranges enforced by stops ({:g} per rad or m{})",
                  sim.accuracy,
                  sim.contact_model == dynamics::ContactModel::kSimbody
                      ? "by Simbody's CompliantContactSubsystem (HalfSpace floor; Box shapes as Bricks, other shapes "
                        "as elastic-foundation triangle meshes)"
                      : "at collision vertices",
                  sim.contact_params.friction, sim.contact_params.dissipation, sim.contact_params.transition_velocity,
                  sim.stop_stiffness,
                  command.name == "check"
                      ? fmt::format(", in the generic checks between the joint's subtree inertia × ({:g} rad/s)² and "
                                    "× ({:g} rad/s)²",
                                    dynamics::kGenericStopFloorFrequency, dynamics::kGenericStopFrequency)
                      : ""),
      4);
  if (command.name == "check-tank") {
    auto link = [&](LinkIndex i) { return i >= 0 ? model.links[i].name : std::string("none"); };
    std::cout << wrap(
        fmt::format("  tracks: left \"{}\", right \"{}\" (found by position), spacing B = {} m; turret yaw \"{}\", "
                    "pitch \"{}\", servo P = {:g}, D = {:g}",
                    link(tank.left), link(tank.right), number(tank.spacing), link(tank.yaw), link(tank.pitch),
                    suite.p_gain, suite.d_gain),
        4);
    if (!command.cross_check.empty())
      std::cout << wrap(
          "  cross-check: MuJoCo 2.2.2 on body2mjcf's export (elliptic cones, Euler 1 ms, belt velocity through "
          "mjcb_control), the same commands in both engines; its \"MuJoCo vs Simbody\" lines: measured = MuJoCo, "
          "expected = Simbody",
          4);
  }
}

void print_results(const std::vector<dynamics::CheckResult>& results) {
  int self_tests = 0;
  for (const auto& r : results) self_tests += r.self_test ? 1 : 0;
  if (self_tests > 0) {
    std::cout << "self-test of the Simbody build (its system against the derived data it was built from):\n";
    for (const auto& r : results)
      if (r.self_test) std::cout << check_lines(r);
    std::cout << "checks of the model:\n";
  }
  int passed = 0, failed = 0, skipped = 0;
  for (const auto& r : results) {
    if (!r.self_test) std::cout << check_lines(r);
    (r.skipped ? skipped : r.passed ? passed : failed) += 1;
  }
  std::cout << fmt::format("{} of {} checks passed, {} failed, {} skipped\n", passed, passed + failed, failed, skipped);
}

}  // namespace bodyfmt::tools
