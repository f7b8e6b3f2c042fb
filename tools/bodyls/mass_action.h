#pragma once
/// The "compute this link's centre of mass and inertia from its shapes" action (issue 47): what
/// `bodycheck --fix=geometry` writes for a flagged link, offered for the link at the cursor
/// whatever the rules say: the link-level keys and every RigidBody element with shapes. A thin
/// caller of the library's per-link computation (link_geometry_mass, geometry_at_written_mass,
/// link_mass_fixes, rigid_body_mass_fixes).

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::lsp {

struct MassFromShapes {
  std::string title;
  std::vector<FixIt> fixes;  ///< empty when `unavailable` says why
  std::string unavailable;
  bool flagged = false;  ///< an inertia rule reports at the link (the action is then its quick fix)
};

/// The action for the link of `model` whose text holds the 1-based `line` of the document
/// `path` (the last link starting at or before it), or nothing when no link of that file
/// starts there. `text` is the document's text, `findings` its check's.
std::optional<MassFromShapes> mass_from_shapes(const Model& model, const std::string& path, const std::string& text,
                                               const std::vector<Diagnostic>& findings, int line);

}  // namespace bodyfmt::lsp
