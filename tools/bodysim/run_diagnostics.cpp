#include "run_diagnostics.h"

#include "report_lines.h"

#include <iostream>

namespace bodyfmt::tools {

RunDiagnostics::RunDiagnostics(Front& front, const Front::FilePolicy& policy)
    : front_(front), exit_(policy.exit), sink_(collected_, policy.options) {}

int RunDiagnostics::finish(bool fatal, const std::string& why) {
  front_.print(collected_.diagnostics());
  // The reason ends the run, with the first error that stopped it: after a hundred warnings
  // (legacy keys, say) "see above" would point nowhere.
  if (why.find("nothing was simulated") != std::string::npos)
    std::cerr << nothing_simulated(front_.tool_name(), why, collected_.diagnostics());
  else if (!why.empty())
    front_.print_error(why);
  return exit_code(collected_.diagnostics(), exit_, fatal);
}

}  // namespace bodyfmt::tools
