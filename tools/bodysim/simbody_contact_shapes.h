#pragma once
/// Which collision shapes Simbody's compliant contact (--contact simbody) takes.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

namespace bodyfmt::tools {

/// True when every collision shape of `model` is one Simbody's contact takes (a Box, as a
/// Brick); otherwise reports the first other one (dynamics-contact-geometry) and returns false.
bool simbody_takes_contact_shapes(const Model& model, DiagnosticSink& sink);

}  // namespace bodyfmt::tools
