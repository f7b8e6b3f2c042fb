#include "mass_report.h"

#include <bodyfmt/inertia.h>
#include <bodyfmt/readable_number.h>

#include <fmt/format.h>

#include <cmath>

namespace bodyfmt::tools {
namespace {

// Finite numbers to round-trip (17 significant digits at most, the shortest that reads back);
// JSON has no infinity, so a non-finite value is null in both forms.
std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  if (v == 0) return "0";
  return fmt::format("{}", v);
}

// For people: `13.5` where the arithmetic left 13.500000000000002 (bodyfmt/readable_number.h).
std::string readable(double v) { return readable_number(v); }

using NumberText = std::string (*)(double);

template <typename Vector>
std::string list(const Vector& v, NumberText text = number) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + text(v[i]);
  return out + "]";
}

std::string tensor(const Eigen::Matrix3d& m, NumberText text = number) {
  std::string out = "[";
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out += (r || c ? ", " : "") + text(m(r, c));
  return out + "]";
}

Eigen::Vector3d moments(const MassProperties& m) {
  if (!m.inertia.allFinite()) return Eigen::Vector3d::Constant(NAN);
  return principal_inertia(m.inertia).moments;
}

/// JSON string: the link names are UTF-8 as loaded; quotes, backslashes and controls escaped.
std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\')
      out += std::string("\\") + ch;
    else if (c < 0x20 || c == 0x7f)
      out += fmt::format("\\u{:04x}", c);
    else
      out += ch;
  }
  return out + "\"";
}

// One mapping of mass properties, in the flow form that YAML and JSON share.
std::string properties(const std::optional<MassProperties>& m, bool with_mass = true) {
  if (!m) return "null";
  std::string out = "{";
  if (with_mass) out += "\"mass\": " + number(m->mass) + ", ";
  out += "\"center_of_mass\": " + list(m->center_of_mass) + ", \"inertia\": " + tensor(m->inertia) +
         ", \"principal_moments\": " + list(moments(*m)) + "}";
  return out;
}

std::string shapes_word(const LinkGeometryMass& g) { return g.from_visual ? "visual" : "collision"; }

std::string structured(const Model& model, const Derived& derived, double density,
                       const std::vector<LinkMassComparison>& links, bool json) {
  // JSON is valid YAML in flow form; the YAML form puts each link on block lines for reading.
  std::string out;
  out += json ? "{\"density\": " + number(density) + ", \"links\": [\n" : "density: " + number(density) + "\nlinks:\n";
  for (std::size_t i = 0; i < links.size(); ++i) {
    const LinkMassComparison& c = links[i];
    const std::optional<MassProperties> written = derived.mass[i];
    const std::optional<MassProperties> at_mass =
        c.at_written_mass ? std::optional<MassProperties>(c.at_written_mass->combined) : std::nullopt;
    const std::string fields[][2] = {
        {"name", json_string(model.links[i].name)},
        {"shapes", json_string(shapes_word(c.geometry))},
        {"solids", std::to_string(c.geometry.solids)},
        {"solids_in_rigid_bodies", std::to_string(c.geometry.solids_in_rigid_bodies())},
        {"left_out", std::to_string(c.geometry.left_out)},
        {"volume", number(c.geometry.volume.mass)},
        {"written", properties(written)},
        {"computed", properties(c.at_density)},
        {"computed_at_written_mass", properties(at_mass)},
    };
    if (json) {
      out += "  {";
      for (std::size_t f = 0; f < std::size(fields); ++f)
        out += (f ? ", " : "") + json_string(fields[f][0]) + ": " + fields[f][1];
      out += i + 1 < links.size() ? "},\n" : "}\n";
    } else {
      for (std::size_t f = 0; f < std::size(fields); ++f)
        out += (f ? "    " : "  - ") + fields[f][0] + ": " + fields[f][1] + "\n";
    }
  }
  if (json) out += "]}\n";
  return out;
}

// What float arithmetic leaves where a person expects 0 (a tensor turned by 90 degrees has
// 1e-18 off its diagonal; a centre of mass on an axis, 1e-21 beside it) is shown as 0: below a
// picometre, or 1e-12 of a tensor's largest entry.
std::string point(const Eigen::Vector3d& c) {
  return list(Eigen::Vector3d(c.unaryExpr([](double v) { return std::abs(v) < 1e-12 ? 0.0 : v; })), readable);
}
std::string moments_of(const Eigen::Matrix3d& m) {
  const double scale = m.cwiseAbs().maxCoeff();
  return tensor(m.unaryExpr([scale](double v) { return std::abs(v) <= 1e-12 * scale ? 0.0 : v; }), readable);
}

std::string text(const Model& model, const Derived& derived, double density,
                 const std::vector<LinkMassComparison>& links) {
  std::string out = fmt::format("{}: mass properties from the geometry at {} kg/m³ (written | computed)\n", model.name,
                                readable(density));
  for (std::size_t i = 0; i < links.size(); ++i) {
    const LinkMassComparison& c = links[i];
    const MassProperties& w = derived.mass[i];
    out += fmt::format("{}  ({} shapes: {} solid{}", model.links[i].name, shapes_word(c.geometry), c.geometry.solids,
                       c.geometry.solids == 1 ? "" : "s");
    if (!c.geometry.empty()) out += fmt::format(" of volume {} m³", readable(c.geometry.volume.mass));
    // Shapes below a RigidBody element weigh what it says: counted once, as written.
    if (const int inside = c.geometry.solids_in_rigid_bodies(); inside > 0)
      out += fmt::format(", {} more below RigidBody elements (their mass as written)", inside);
    if (c.geometry.left_out > 0) out += fmt::format(", {} left out", c.geometry.left_out);
    out += ")\n";
    const auto row = [&](const char* what, const std::string& written, const std::string& computed) {
      out += fmt::format("  {:<18} {} | {}\n", what, written, computed);
    };
    const std::string none = "-";
    row("mass", readable(w.mass), c.at_density ? readable(c.at_density->mass) : none);
    row("center_of_mass", point(w.center_of_mass), c.at_density ? point(c.at_density->center_of_mass) : none);
    row("inertia", moments_of(w.inertia), c.at_density ? moments_of(c.at_density->inertia) : none);
    row("principal moments", list(moments(w), readable), c.at_density ? list(moments(*c.at_density), readable) : none);
    if (c.at_written_mass) {
      const MassProperties& m = c.at_written_mass->combined;
      out += fmt::format("  at the written mass {}: center_of_mass {}, inertia {}, principal moments {}\n",
                         readable(m.mass), point(m.center_of_mass), moments_of(m.inertia), list(moments(m), readable));
    }
  }
  return out;
}

}  // namespace

std::vector<LinkMassComparison> compare_mass_with_geometry(const Model& model, double density, DiagnosticSink& sink) {
  std::vector<LinkMassComparison> result;
  result.reserve(model.links.size());
  for (const Link& link : model.links) {
    LinkMassComparison c;
    c.geometry = link_geometry_mass(model, link, sink);
    c.at_density = link_mass_from_geometry(link, c.geometry, density);
    c.at_written_mass = geometry_at_written_mass(link, c.geometry);
    result.push_back(std::move(c));
  }
  return result;
}

std::string format_mass_comparison(const Model& model, const Derived& derived, double density,
                                   const std::vector<LinkMassComparison>& links, const std::string& format) {
  if (format == "text") return text(model, derived, density, links);
  return structured(model, derived, density, links, format == "json");
}

}  // namespace bodyfmt::tools
