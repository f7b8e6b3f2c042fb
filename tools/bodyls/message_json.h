#pragma once
/// The one place bodyls reads a message body as JSON. nlohmann::json's values copy, compare,
/// dump and destroy themselves recursively, so a body nested 200,000 arrays deep would
/// overflow the stack in any of them: the nesting is bounded before the text is parsed.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string_view>

namespace bodyfmt::lsp {

/// Nesting of arrays and objects a message may have; LSP's deepest messages (a workspace edit
/// in a code action, nested document symbols) are far below it.
constexpr std::size_t kMostMessageDepth = 256;

/// True when `text`, read as JSON, opens more than `limit` arrays and objects inside each
/// other (brackets inside strings do not count). One pass over the bytes, no recursion; it
/// does not check that the text is JSON.
bool nests_deeper_than(std::string_view text, std::size_t limit);

enum class MessageParse { kOk, kNotJson, kTooDeep };

/// `body` parsed into `out` (discarded unless kOk).
MessageParse parse_message(std::string_view body, nlohmann::json& out);

}  // namespace bodyfmt::lsp
