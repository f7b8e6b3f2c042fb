#pragma once
// What the model knows about a link, for hover: its mass, its subtree's combined mass, its
// joint type and its world frame at the initial pose (libbodyfmt's mass and pose code).

#include "hover_text.h"
#include "language_features.h"

#include <optional>
#include <string>
#include <string_view>

namespace bodyfmt::lsp {

/// What the hover says about link `name` of the document's model; nullopt when no model is
/// loaded or it has no such link.
std::optional<HoverText> link_hover(const Document& document, std::string_view name);

}  // namespace bodyfmt::lsp
