#pragma once
/// The fix-its of `bodycheck --fix=geometry` (issue 39): a link's centre of mass and inertia
/// replaced by those of its shapes at its written mass. They change the model, so they are
/// FixSafety::kUnsafe: plain `--fix` never applies them, only `--fix=geometry` asks for them.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// Fix-its that write `keys` (a centre of mass and an inertia about it) over the link-level
/// `center_of_mass` and `inertia` of `link`, read from `text`, the file those keys are written
/// in (named `file`). Each number is replaced where it is written, so the file keeps its form (6
/// or 9 inertia numbers, flow or block); a missing `center_of_mass` or `inertia` is inserted as a
/// line of its own before the link's `mass` key. Numbers are written with 9 significant digits
/// (17 where 9 would break the triangle inequality), entries within 1e-12 of the largest as 0.
/// Returns nothing, with `why` set, when a value is not written as plain numbers in place (an
/// alias, a merge key, a quoted or block scalar, a flow mapping) or the link has no `mass` key.
std::vector<FixIt> link_mass_fixes(std::string_view text, const std::string& file, const Link& link,
                                   const MassProperties& keys, std::string& why);

/// The same for the RigidBody element that is `link`'s mass contribution `contribution`: `keys`
/// in the element's own frame (RecomputedRigidBody::as_written) over its `center_of_mass` and
/// `inertia`, found in `text` by the element's location. Nothing, with `why`, when the element is
/// reached through an alias or its numbers are not written in place, or it has no `mass` key.
std::vector<FixIt> rigid_body_mass_fixes(std::string_view text, const std::string& file, const Link& link,
                                         std::size_t contribution, const MassProperties& keys, std::string& why);

/// The numbers link_mass_fixes and rigid_body_mass_fixes write for `keys`, as they read back.
MassProperties written_mass_keys(const MassProperties& keys);

/// The links `--fix=geometry` replaces the centre of mass and inertia of: those that
/// inertia-implausible, -triangle, -not-positive-definite or -com-outside report at (the link,
/// its mass keys or one of its RigidBody elements), among `findings`.
std::vector<bool> links_for_geometry_fix(const Model& model, const std::vector<Diagnostic>& findings);

}  // namespace bodyfmt
#pragma GCC visibility pop
