#pragma once
/// The one line every exporter ends with once its output is written: what was written, where
/// the generated files went, the losses counted by kind and the option that accepts them. The
/// findings above it can run to hundreds of lines; this line is what a user reads first.

#include "front.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/diagnostic.h>

#include <string>
#include <vector>

namespace bodyfmt::tools {

/// "wrote out/a.urdf and 12 mesh files in out/meshes/a; lost 21 dynamics, 1 devices (exit 1;
/// --allow-loss dynamics,devices accepts them)" or "...; nothing lost". Kinds already accepted
/// by `policy` are counted but not offered again.
std::string export_summary(const converters::OutputSet& out, const std::vector<Diagnostic>& diagnostics,
                           const ExitPolicy& policy);

}  // namespace bodyfmt::tools
