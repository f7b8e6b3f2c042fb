#pragma once
/// Validation rules over a loaded model (bodycheck). Rules read the Model and its Derived
/// data and never reopen the file; what only the loader can see (syntax, keys, types) is
/// reported by the loader.

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <string>

namespace bodyfmt::validate {

struct CheckOptions {
  /// Relative tolerance for the symmetry of a 9-element inertia.
  double inertia_symmetry_tolerance = 1e-6;
  /// An inertia more than this factor away from the one implied by the geometry and mass is
  /// reported as implausible (either direction).
  double inertia_plausibility_factor = 10.0;
};

/// Runs every rule family and reports `inertia-*`, `joint-*`, `units-*`, `structure-*`,
/// `geometry-*`, `resource-*` and `device-*` findings with their default severities.
void check_model(const Model& model, const Derived& derived, const CheckOptions& options, DiagnosticSink& sink);

/// Every rule of the rule table (loader and validator) as the Markdown of docs/rules.md:
/// id, default severity, summary, rationale and tolerance, grouped by family.
std::string rules_markdown();

}  // namespace bodyfmt::validate
