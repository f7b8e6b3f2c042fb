#pragma once
/// What bodysim's command line asks for: the subcommand that ran and its options. Only one
/// subcommand runs, so they share the variables their options set.

#include <bodyfmt/dynamics/checks.h>
#include <bodyfmt/dynamics/scenario.h>

#include <cstddef>
#include <string>

namespace bodyfmt::tools {

struct SimCommand {
  std::string name;                  ///< check-tank, check or run
  dynamics::TankSuiteOptions suite;  ///< suite.sim: the simulation options of every subcommand
  std::size_t max_links = 200;
  std::string cross_check;              ///< check-tank and check: "mujoco", or empty
  std::string scenario_path, csv_path;  ///< run
  dynamics::ScenarioLimits limits;      ///< run
};

}  // namespace bodyfmt::tools
