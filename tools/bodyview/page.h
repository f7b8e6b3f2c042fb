#pragma once
// bodyview's page: one self-contained HTML file holding the model as GLB (body2gltf's writer,
// visual and collision), what the viewer shows beside it (joints, mass, inertia and the shapes'
// inertia with bodycheck --fix=geometry's values, devices, sources, bodycheck's findings) as
// JSON, the viewer script and three.js, all inline.

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>
#include <bodyfmt/report.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::bodyview {

/// The viewer's files (viewer.html, viewer.js, viewer.css and three.js's modules) as the build
/// vendored them: beside the installed tool, else in the build tree. Empty when not found.
std::filesystem::path find_assets(const char* argv0);

/// What the page shows for one load of the model.
struct PageInput {
  const Model* model = nullptr;
  const Derived* derived = nullptr;
  std::string glb;                   ///< the GLB bytes
  std::vector<Diagnostic> findings;  ///< loader and bodycheck findings, sorted
  SourceLines* sources = nullptr;    ///< for the caret text of each finding
  std::string serve_status_url;      ///< --serve: the page polls this; empty for a file
};

/// The page's JSON: links, joints, devices, findings (the window.bodyview data).
std::string page_data_json(const PageInput& input);

/// The whole HTML page; nullopt with `error` set when an asset cannot be read.
std::optional<std::string> build_page(const std::filesystem::path& assets, const PageInput& input, std::string& error);

}  // namespace bodyfmt::bodyview
