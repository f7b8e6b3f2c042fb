#pragma once
// Hover text written once for both forms a client may ask for (LSP's MarkupContent): Markdown,
// with what the file holds escaped or in code spans so that a name renders as written, and
// plain text, which has no markup at all (a client without a Markdown renderer, such as
// Emacs 28's eglot without markdown-mode, shows Markdown as its raw characters).

#include <string>
#include <string_view>

namespace bodyfmt::lsp {

class HoverText {
 public:
  /// Words as they are: escaped in Markdown where they would otherwise be markup.
  HoverText& text(std::string_view words);
  /// Emphasised words (a heading of the hover): **words** in Markdown.
  HoverText& bold(std::string_view words);
  /// Text of the file or a key's name, verbatim: a code span in Markdown.
  HoverText& code(std::string_view verbatim);
  /// A new paragraph.
  HoverText& paragraph();

  const std::string& markdown() const { return markdown_; }
  const std::string& plain() const { return plain_; }

 private:
  std::string markdown_;
  std::string plain_;
};

}  // namespace bodyfmt::lsp
