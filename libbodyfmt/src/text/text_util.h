#pragma once
// Small text utilities below the loader and the diagnostics: did-you-mean spelling, the YAML
// 1.1 boolean words and line splitting. No YAML, no model. (JSON and XML quoting are public:
// bodyfmt/text.h.)

#include <bodyfmt/text.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::text {

/// Case-insensitive edit distance counting adjacent transpositions as one edit (optimal
/// string alignment), for did-you-mean hints.
int edit_distance(std::string_view a, std::string_view b);

/// The closest of `candidates` to `word` if it is a plausible typo, else empty.
std::string_view suggest(std::string_view word, const std::vector<std::string_view>& candidates);
/// Every candidate as close to `word` as the closest, in the order given, if that is a
/// plausible typo (suggest's distance), else none: a did-you-mean may have more than one answer.
std::vector<std::string_view> nearest(std::string_view word, const std::vector<std::string_view>& candidates);

/// The boolean words of body-format-spec §1.3 (YAML 1.1: y/yes/true/on and n/no/false/off in
/// three cases), exactly; nullopt for anything else.
std::optional<bool> parse_bool_word(std::string_view word);

/// Splits text into lines (LF or CRLF), without the breaks.
std::vector<std::string> split_lines(std::string_view text);
/// The same lines as views into `text`, without copying them.
std::vector<std::string_view> line_views(std::string_view text);

/// Appends `text` so that it stays on one line and moves no terminal: line breaks (LF, CR,
/// NEL, U+2028, U+2029) and the other C0 and C1 controls and DEL are written as escapes
/// (`\n`, `\r`, `\x1b`, `\u0085`); tabs and everything else are kept as they are.
void append_one_line(std::string& out, std::string_view text);

}  // namespace bodyfmt::text
