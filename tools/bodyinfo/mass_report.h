#pragma once
// `bodyinfo --mass-from-geometry`: per link, the written mass properties beside those computed
// from its shapes (issue 39), for people (text) and for programs (JSON, YAML).

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/geometry_mass.h>
#include <bodyfmt/model.h>

#include <string>
#include <vector>

namespace bodyfmt::tools {

/// One link's written and computed mass properties.
struct LinkMassComparison {
  LinkGeometryMass geometry;
  std::optional<MassProperties> at_density;              ///< geometry at the density, with RigidBody elements
  std::optional<GeometryAtWrittenMass> at_written_mass;  ///< geometry at the written link-level mass
};

/// Computes every link's comparison; shapes that are no solid are reported to `sink`.
std::vector<LinkMassComparison> compare_mass_with_geometry(const Model& model, double density, DiagnosticSink& sink);

/// `format`: "text", "json" or "yaml".
std::string format_mass_comparison(const Model& model, const Derived& derived, double density,
                                   const std::vector<LinkMassComparison>& links, const std::string& format);

}  // namespace bodyfmt::tools
