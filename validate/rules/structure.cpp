// Structure rules the loader cannot see on its own (issue 4, "Structure"). Duplicate links,
// unknown parents, cycles, unreachable links and root_link are the loader's (structure-*).

#include "rule_context.h"

#include <fmt/format.h>

#include <map>
#include <utility>

namespace bodyfmt::validate::detail {

// Choreonoid looks devices up by name (Body::findDevice(name) returns the first match;
// findDevice<T>(name) the first of that class), and controllers, ROS bridges and the
// simulator's device views address them by name. Two named devices that share a name are
// therefore reported whatever their types: with the same class the second one can never be
// found; with different classes only typed look-ups tell them apart. One rule, a warning,
// because Choreonoid itself loads the file. Unnamed devices are not looked up by name.
void check_structure(const RuleContext& ctx) {
  std::map<std::string, std::size_t> first;
  for (std::size_t i = 0; i < ctx.model.devices.size(); ++i) {
    const Device& d = ctx.model.devices[i];
    if (d.name.empty()) continue;
    auto [it, inserted] = first.emplace(d.name, i);
    if (inserted) continue;
    const Device& other = ctx.model.devices[it->second];
    const bool same_type = other.type == d.type;
    ctx.report("structure-duplicate-device", d.key_source({"name"}),
               fmt::format("device name \"{}\" ({}) is already used by a {} device (line {}){}", d.name, d.type,
                           other.type, other.key_source({"name"}).line,
                           same_type ? ": look-ups by name only ever find the first one"
                                     : ": only look-ups by type can tell them apart"),
               "give every device its own name");
  }
}

}  // namespace bodyfmt::validate::detail
