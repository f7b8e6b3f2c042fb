#pragma once
// One load of the model for bodyview: load, derive, bodycheck's rules, the GLB, the page.

#include "front.h"
#include "page.h"

#include <bodyfmt/input_files.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::bodyview {

struct Rendered {
  std::optional<std::string> page;      ///< nullopt: nothing to show (fatal, or the page failed)
  std::vector<Diagnostic> diagnostics;  ///< loader, rules and page problems, sorted
  std::vector<InputFile> inputs;        ///< the files read (to protect, and for --serve to watch)
  std::optional<Model> model;           ///< kept for the output's input protection
};

/// Loads `path` through the front's policy and builds the page. `serve_status_url` is empty for
/// a file. The GLB writer's export losses are left out: the page shows tracks, devices and
/// closed loops from the model, not from the GLB.
Rendered render(tools::Front& front, const tools::Front::FilePolicy& policy, const std::string& path,
                const std::filesystem::path& assets, const std::string& serve_status_url);

}  // namespace bodyfmt::bodyview
