#pragma once
/// Hover, completion, definition, references, rename and document symbols in the protocol's
/// terms: converts positions both ways around language_features.h, which works in the
/// project's 1-based lines and byte columns.

#include "language_features.h"
#include "text_positions.h"

#include <bodyfmt/model.h>

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>

namespace bodyfmt::lsp {

struct FeatureDocument {
  std::string uri;
  std::string path;
  std::string text;
  std::shared_ptr<const Model> model;  ///< of the last text that loaded (null: none has)
  bool model_is_current = false;
  /// The open buffers the model read in place of its included files (by canonical path): the
  /// model's positions in them are converted with those texts; other files are read from disk.
  std::shared_ptr<const std::map<std::string, std::string>> model_texts;
  /// The client asked for plain text, not Markdown (prefers_plain_text): hovers are sent so.
  bool plain_text = false;
};

/// Whether the client's `textDocument.<feature>.contentFormat` (its MarkupKinds, the one it
/// prefers first) puts "plaintext" before "markdown", or lists plain text and not Markdown.
/// A client that declares no formats gets Markdown.
bool prefers_plain_text(const nlohmann::json& capabilities, const char* feature);

/// The answer to `method` (textDocument/hover, completion, definition, references,
/// prepareRename, rename, documentSymbol), or nullopt when `method` is none of these.
std::optional<nlohmann::json> answer_feature(const std::string& method, const nlohmann::json& params,
                                             const FeatureDocument& document);

bool is_feature_method(const std::string& method);

/// The protocol's position as the features' point (1-based line, 1-based byte column; past
/// the last line: the end of the last line; inside a character: its start).
TextPoint text_point_of(const TextLines& lines, Utf16Position position);
/// A features' range as the protocol's (clamped to the text).
Utf16Range utf16_range_of(const TextLines& lines, const TextRange& range);

}  // namespace bodyfmt::lsp
