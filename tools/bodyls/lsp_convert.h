#pragma once
/// The project's findings and positions in the protocol's terms: 1-based lines and byte
/// columns to 0-based UTF-16 ranges of the right file's text, a Diagnostic to an LSP
/// Diagnostic on its file's URI.

#include "text_positions.h"

#include <bodyfmt/diagnostic.h>

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::lsp {

/// The code action kind that asks for the format 1.0 -> 2.0 upgrade (docs/tools/bodyls.md).
inline constexpr const char* kUpgradeActionKind = "quickfix.bodyfmt.upgrade";

Utf16Position position_from_json(const nlohmann::json& position);
Utf16Range range_from_json(const nlohmann::json& range);
nlohmann::json to_json(Utf16Position position);
nlohmann::json to_json(Utf16Range range);

/// The texts of the files findings point at: the document's buffer, other open buffers (by
/// canonical path), else the file on disk (read once). Positions are converted with the text
/// that was checked.
class FileTexts {
 public:
  FileTexts(std::string document_path, std::string document_uri, const std::string& document_text,
            const std::map<std::string, std::string>& other_texts);

  /// The text of `file` (a path as the loader names it), or null when it cannot be read.
  const std::string* text(const std::string& file);
  const TextLines* lines(const std::string& file);
  /// The URI a finding in `file` is published on (the document's own URI for its path).
  std::string uri(const std::string& file) const;
  /// The UTF-16 range of the token at a 1-based line and byte column of `file` (unknown
  /// positions: the file's start).
  Utf16Range token_range(const std::string& file, int line, int column);
  /// The UTF-16 range of the bytes [begin, end) of `file`.
  std::optional<Utf16Range> byte_range(const std::string& file, std::size_t begin, std::size_t end);

 private:
  std::string document_path_;
  std::string document_uri_;
  const std::string& document_text_;
  const std::map<std::string, std::string>& other_texts_;
  std::map<std::string, std::unique_ptr<std::string>> read_;
  std::map<std::string, std::unique_ptr<TextLines>> lines_;
};

/// One finding as an LSP Diagnostic: code = rule id, source "bodyfmt", the severity, the range
/// of the token at its location, the alias it came through and its fix hint as related
/// information.
nlohmann::json diagnostic_to_json(const Diagnostic& d, FileTexts& texts);

}  // namespace bodyfmt::lsp
