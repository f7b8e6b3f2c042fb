#pragma once
/// Our own VRML97 geometry reader (see VRML_READER.md for why not Coin3D): a recursive-descent
/// parser over VrmlLexer for the node subset Choreonoid's body models use, producing the
/// format-neutral SceneNode tree.

#include "mesh_import/scene_tree.h"

#include <bodyfmt/diagnostic.h>

#include <functional>
#include <string>
#include <string_view>

namespace bodyfmt::mesh {

/// Loads an Inline'd file (already resolved to a path). Returns nullptr after reporting when
/// it cannot be read. Lets the mesh cache parse each file once and detect Inline cycles.
using InlineLoader = std::function<SceneTree(const std::string& resolved_path, const SourceLocation& where)>;

/// Parses VRML97 `text`; `path` is used for diagnostics and for resolving relative `url`s
/// (Inline, ImageTexture). On a syntax error, reports `mesh-parse` at file:line:col and
/// returns nullptr. `load_inline` may be empty: Inline nodes are then left empty.
SceneTree read_vrml(std::string_view text, const std::string& path, DiagnosticSink& sink,
                    const InlineLoader& load_inline);

/// Resolves a VRML url (relative to the directory of `base_file`, `file://` accepted).
std::string resolve_relative(const std::string& base_file, const std::string& url);

}  // namespace bodyfmt::mesh
