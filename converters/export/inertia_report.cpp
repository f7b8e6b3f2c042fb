#include <bodyfmt/converters/inertia_report.h>
#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/inertia.h>

#include <fmt/format.h>

namespace bodyfmt::converters {

std::string tensor_text(const Eigen::Matrix3d& I) {
  return fmt::format("[{}, {}, {}, {}, {}, {}]", format_number(I(0, 0)), format_number(I(0, 1)), format_number(I(0, 2)),
                     format_number(I(1, 1)), format_number(I(1, 2)), format_number(I(2, 2)));
}

std::string moments_text(const Eigen::Vector3d& m) {
  return fmt::format("({}, {}, {})", format_number(m[0]), format_number(m[1]), format_number(m[2]));
}

std::string inertia_defect_text(const PhysicalFinding& f) {
  return f.validity.negative_moment ? "a negative moment"
                                    : fmt::format("A + B - C = {}", format_number(f.validity.triangle_margin));
}

std::string nearest_inertia_hint(const PhysicalFinding& f) {
  return f.balanced ? "nearest valid inertia (link axes, about the centre of mass): " + tensor_text(*f.balanced) : "";
}

std::string balanced_inertia_text(const Link& link, const PhysicalFinding& f, const Eigen::Matrix3d& before,
                                  const Eigen::Matrix3d& after) {
  return fmt::format(
      "the inertia {} of link \"{}\" (principal moments {}, {}); written balanced (--balance-inertia, "
      "bodyfmt::balance_inertia) as {} (principal moments {})",
      tensor_text(before), link.name, moments_text(f.principal.moments), inertia_defect_text(f), tensor_text(after),
      moments_text(principal_inertia(after).moments));
}

std::string asymmetric_inertia_text(const Link& link, const PhysicalFinding& f) {
  const Eigen::Matrix3d& I = link.mass_contributions[f.contribution].inertia;
  const char* axis = "xyz";
  const int row = f.row, col = f.column;
  return fmt::format(
      "the inertia [{}, {}, {}, {}, {}, {}, {}, {}, {}] of link \"{}\" is not symmetric: I{}{} = {} but "
      "I{}{} = {}",
      format_number(I(0, 0)), format_number(I(0, 1)), format_number(I(0, 2)), format_number(I(1, 0)),
      format_number(I(1, 1)), format_number(I(1, 2)), format_number(I(2, 0)), format_number(I(2, 1)),
      format_number(I(2, 2)), link.name, axis[row], axis[col], format_number(I(row, col)), axis[col], axis[row],
      format_number(I(col, row)));
}

Eigen::Matrix3d symmetrised_contribution(const Link& link, const PhysicalFinding& f) {
  return symmetrized_inertia(link.mass_contributions[f.contribution].inertia);
}

void report_asymmetric_inertia_refused(DiagnosticSink& sink, const Link& link, const PhysicalFinding& f,
                                       std::string_view holds) {
  report_physical(sink, f,
                  asymmetric_inertia_text(link, f) + "; " + std::string(holds) + ", so the model is not written",
                  "write the 6-element form [Ixx, Ixy, Ixz, Iyy, Iyz, Izz] with the values you mean; "
                  "--balance-inertia writes the mean of each off-diagonal pair");
}

std::string symmetrised_inertia_text(const Link& link, const PhysicalFinding& f) {
  return asymmetric_inertia_text(link, f) +
         fmt::format("; written symmetrised (--balance-inertia, the mean of each off-diagonal pair) as {}",
                     tensor_text(symmetrised_contribution(link, f)));
}

}  // namespace bodyfmt::converters
