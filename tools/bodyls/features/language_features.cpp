// Placeholder: the features answer nothing yet (the helper that builds them replaces this file).
#include "language_features.h"

namespace bodyfmt::lsp {

std::optional<Hover> hover(const Document&, TextPoint) { return std::nullopt; }
std::vector<CompletionItem> complete(const Document&, TextPoint) { return {}; }
std::vector<FileRange> definition(const Document&, TextPoint) { return {}; }
std::vector<FileRange> references(const Document&, TextPoint, bool) { return {}; }
std::optional<TextRange> prepare_rename(const Document&, TextPoint, std::string& why) {
  why = "not implemented";
  return std::nullopt;
}
std::optional<std::vector<TextEdit>> rename_link(const Document&, TextPoint, const std::string&, std::string& why) {
  why = "not implemented";
  return std::nullopt;
}
std::vector<Symbol> document_symbols(const Document&) { return {}; }

}  // namespace bodyfmt::lsp
