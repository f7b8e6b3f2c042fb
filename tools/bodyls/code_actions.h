#pragma once
/// textDocument/codeAction: the fix-its of the findings in a range as quick fixes, with
/// `bodycheck --fix`'s safety classes. Safe fix-its are offered as preferred `quickfix` edits;
/// the format 1.0 -> 2.0 upgrade (all of its edits together, as `--fix --upgrade` applies them)
/// only when the client asks for kUpgradeActionKind (or "quickfix.bodyfmt") in
/// `context.only`; an unsafe fix-it (one that changes the model, which `bodycheck --fix` never
/// applies) is a `quickfix` edit the user may choose, never preferred and never of a bulk kind.
/// With the document's model, the link at the cursor gets "compute its centre of mass and
/// inertia from its shapes" (mass_action.h): a `quickfix` when an inertia rule flags the link,
/// else kMassFromShapesKind; shown disabled with the reason when it cannot be computed.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <nlohmann/json.hpp>

#include "text_positions.h"

#include <memory>
#include <string>
#include <vector>

namespace bodyfmt::lsp {

struct CodeActionQuery {
  Utf16Range range;
  std::vector<std::string> only;  ///< context.only (empty: every kind)
  bool disabled_support = false;  ///< the client shows disabled actions
  /// The model of the text checked, when that text loaded: the per-link actions need it.
  std::shared_ptr<const Model> model;
};

/// The kind of "compute the centre of mass and inertia from the shapes" on a link no rule flags.
inline constexpr const char* kMassFromShapesKind = "refactor.rewrite.bodyfmt.massFromShapes";

/// The actions for the findings of the checked `text` of the document `path` at `uri`.
nlohmann::json code_actions_for(const std::string& uri, const std::string& path, const std::string& text,
                                const std::vector<Diagnostic>& findings, const CodeActionQuery& query);

}  // namespace bodyfmt::lsp
