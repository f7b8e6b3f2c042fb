// libFuzzer target: bodysim's scenario reader and its limits (issue 26) on a fixed tank model
// with tracks and servoed joints. Oracle: no crash, leak or undefined behaviour; a scenario that
// is accepted is within the limits, its commands in time order, its gains not negative.
#include "fuzz_files.h"

#include <bodyfmt/dynamics/scenario.h>
#include <bodyfmt/load.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace {

const char* const kModel = R"(format: ChoreonoidBody
format_version: 2.0
name: FuzzTank
links:
  - {name: HULL, joint_type: free, mass: 10, inertia: [1, 0, 0, 0, 1, 0, 0, 0, 1]}
  - {name: TRACK_L, parent: HULL, joint_type: pseudo_continuous_track, joint_axis: Y, mass: 1,
     inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]}
  - {name: TRACK_R, parent: HULL, joint_type: pseudo_continuous_track, joint_axis: Y, mass: 1,
     inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]}
  - {name: TURRET_Y, parent: HULL, joint_type: revolute, joint_axis: Z, joint_id: 0, mass: 1,
     inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]}
  - {name: SLIDER, parent: TURRET_Y, joint_type: prismatic, joint_axis: X, joint_id: 1, mass: 1,
     inertia: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]}
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bodyfmt::Model model = [] {
    bodyfmt::CollectingSink sink;
    auto m = bodyfmt::load_body_string(kModel, "tank.body", bodyfmt::LoadOptions{}, sink);
    if (!m) std::abort();
    return *m;
  }();
  const std::string path = fuzz::write_folder(data, size);  // the scenario, as bodysim reads it
  bodyfmt::CollectingSink sink;
  const auto scenario = bodyfmt::dynamics::read_scenario(path, model, sink);
  if (!scenario) return 0;
  bodyfmt::dynamics::ScenarioLimits limits;
  if (!bodyfmt::dynamics::check_scenario(*scenario, limits, sink)) return 0;
  bool ok = scenario->duration > 0 && scenario->duration <= limits.max_duration && scenario->sample > 0 &&
            scenario->duration / scenario->sample <= limits.max_rows;
  double last = 0;
  for (const auto& command : scenario->commands) {
    ok = ok && std::isfinite(command.time) && command.time >= last;
    last = command.time;
    for (const auto& [link, servo] : command.joints) ok = ok && servo.p.value_or(0) >= 0 && servo.d.value_or(0) >= 0;
  }
  if (!ok) {
    std::fprintf(stderr, "an accepted scenario breaks a limit\n");
    std::abort();
  }
  return 0;
}
