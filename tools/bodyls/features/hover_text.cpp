#include "hover_text.h"

#include <algorithm>
#include <cctype>

namespace bodyfmt::lsp {
namespace {

bool word_character(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; }

/// `words` with a backslash before each character that would start Markdown markup there.
/// Not every punctuation mark: a client that shows the Markdown source (Neovim's float) shows
/// the backslashes too.
std::string escaped(std::string_view words) {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const char c = words[i];
    const char before = i > 0 ? words[i - 1] : ' ';
    const char after = i + 1 < words.size() ? words[i + 1] : ' ';
    bool escape = c == '\\' || c == '`' || c == '<';
    // `*` between two spaces and `_` between two letters or digits are no emphasis (CommonMark).
    if (c == '*') escape = !(before == ' ' && after == ' ');
    if (c == '_') escape = !(word_character(before) && word_character(after));
    if (escape) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

HoverText& HoverText::text(std::string_view words) {
  markdown_ += escaped(words);
  plain_ += words;
  return *this;
}

HoverText& HoverText::bold(std::string_view words) {
  markdown_ += "**" + escaped(words) + "**";
  plain_ += words;
  return *this;
}

HoverText& HoverText::code(std::string_view verbatim) {
  // A code span's fence is longer than any run of backticks inside it, and a space pads a
  // backtick at either end (CommonMark).
  std::size_t longest = 0;
  for (std::size_t i = 0; i < verbatim.size();) {
    std::size_t run = 0;
    while (i + run < verbatim.size() && verbatim[i + run] == '`') ++run;
    longest = std::max(longest, run);
    i += run ? run : 1;
  }
  const std::string fence(longest + 1, '`');
  const bool pad = !verbatim.empty() && (verbatim.front() == '`' || verbatim.back() == '`');
  markdown_ += fence + (pad ? " " : "") + std::string(verbatim) + (pad ? " " : "") + fence;
  plain_ += verbatim;
  return *this;
}

HoverText& HoverText::paragraph() {
  markdown_ += "\n\n";
  plain_ += "\n\n";
  return *this;
}

}  // namespace bodyfmt::lsp
