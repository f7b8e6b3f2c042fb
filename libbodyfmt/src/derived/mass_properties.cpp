#include <bodyfmt/derived.h>
#include <bodyfmt/geometry_mass.h>

namespace bodyfmt {

MassProperties compute_mass_properties(const Link& link) { return combine_mass_contributions(link.mass_contributions); }

}  // namespace bodyfmt
