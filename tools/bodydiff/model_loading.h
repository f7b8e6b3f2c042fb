#pragma once
// How bodydiff loads the two sides: quietly, since a model's own findings are bodycheck's
// business; only a model that cannot be loaded at all stops bodydiff, with its errors.

#include "front.h"

#include <bodyfmt/model.h>

#include <optional>
#include <string>

namespace bodyfmt::tools {

/// Loads `path` (a file, or - for standard input); with a `name`, `path` is a git temporary
/// file loaded under the work-tree path `name`, so that relative URIs resolve there and
/// locations name it. Prints the errors of a model that cannot be loaded.
std::optional<Model> load_quietly(Front& front, const std::string& path, const std::string& name);

/// The same for a text read from git, loaded under the work-tree path `name`.
std::optional<Model> load_text_quietly(Front& front, const std::string& text, const std::string& name);

}  // namespace bodyfmt::tools
