#pragma once
/// How the exporters word an inertia the physical-validity gate (bodyfmt/physical.h) finds not
/// physical (kNotPositiveDefinite, kTriangle) or not symmetric (kInertiaAsymmetric), so that
/// body2mjcf and body2urdf give the same numbers in the same words: the tensor as written, its
/// principal moments and defect, the nearest valid tensor (balance_inertia, the gate's
/// `balanced`), and what --balance-inertia wrote instead.
#include <bodyfmt/model.h>
#include <bodyfmt/physical.h>

#include <Eigen/Core>

#include <string>
#include <string_view>

namespace bodyfmt::converters {

/// "[Ixx, Ixy, Ixz, Iyy, Iyz, Izz]" (the upper triangle, shortest round-trip numbers).
std::string tensor_text(const Eigen::Matrix3d& inertia);
/// "(A, B, C)".
std::string moments_text(const Eigen::Vector3d& moments);
/// Why the tensor of `finding` is refused: "a negative moment" or "A + B - C = x".
std::string inertia_defect_text(const PhysicalFinding& finding);
/// The fix hint: "nearest valid inertia (link axes, about the centre of mass): [...]", or empty
/// when balancing leaves nothing.
std::string nearest_inertia_hint(const PhysicalFinding& finding);
/// What an export changed under --balance-inertia, for its export-value-changed report:
/// "the inertia [...] of link "NAME" (principal moments (...), DEFECT); written balanced
/// (--balance-inertia, bodyfmt::balance_inertia) as [...] (principal moments (...))".
std::string balanced_inertia_text(const Link& link, const PhysicalFinding& finding, const Eigen::Matrix3d& before,
                                  const Eigen::Matrix3d& after);
/// An asymmetric tensor (kInertiaAsymmetric), as bodycheck's inertia-asymmetric says it:
/// "the inertia [9 numbers] of link "NAME" is not symmetric: Ixy = a but Iyx = b".
std::string asymmetric_inertia_text(const Link& link, const PhysicalFinding& finding);
/// The 9 numbers of a kInertiaAsymmetric finding's contribution as the symmetric tensor an export
/// writes for them: (I + Iᵀ) / 2, the mean of each off-diagonal pair.
Eigen::Matrix3d symmetrised_contribution(const Link& link, const PhysicalFinding& finding);
/// What an export changed under --balance-inertia for an asymmetric tensor, for its
/// export-value-changed report: asymmetric_inertia_text(), then "; written symmetrised
/// (--balance-inertia, the mean of each off-diagonal pair) as [...]".
std::string symmetrised_inertia_text(const Link& link, const PhysicalFinding& finding);
/// An XML writer's refusal of an asymmetric tensor without --balance-inertia: bodycheck's
/// inertia-asymmetric error at the gate's place, "...; `holds`, so the model is not written",
/// with the hint both writers give (the 6-element form, or --balance-inertia).
void report_asymmetric_inertia_refused(DiagnosticSink& sink, const Link& link, const PhysicalFinding& finding,
                                       std::string_view holds);

}  // namespace bodyfmt::converters
