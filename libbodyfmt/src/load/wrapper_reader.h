#pragma once
// Wrapper body files (body-format-spec §2.4): a .body without `format` whose `model_file` names
// the model, read by the loader its extension selects, with `linkInfo` and
// `geometry: {divisionNumber}` applied as Choreonoid applies them.

#include <bodyfmt/load.h>

#include "load/load_context.h"

#include <optional>
#include <string>

namespace bodyfmt::detail {

struct LoadSession;

/// A top-level mapping without `format` and with `model_file` (or `modelFile`).
bool is_wrapper(const yaml::Node& root);

/// Reads the wrapper whose top-level mapping is `root` (in `file_name`): loads the model file
/// it names (recursively for .body, .yaml and .yml; other formats through
/// LoadOptions::model_file_readers), then applies its keys. Meshes are not imported; the caller
/// does that once for the whole model. nullopt when no model comes out (located errors).
std::optional<Model> read_wrapper(const LoadOptions& options, LoadContext& ctx, LoadSession& session,
                                  const yaml::NodeRef& root, const std::string& file_name);

}  // namespace bodyfmt::detail
