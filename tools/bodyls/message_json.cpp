#include "message_json.h"

namespace bodyfmt::lsp {

bool nests_deeper_than(std::string_view text, std::size_t limit) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;  // the escaped character cannot end the string
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return true;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return false;
}

MessageParse parse_message(std::string_view body, nlohmann::json& out) {
  if (nests_deeper_than(body, kMostMessageDepth)) {
    out = nlohmann::json(nlohmann::json::value_t::discarded);
    return MessageParse::kTooDeep;
  }
  out = nlohmann::json::parse(body, nullptr, false);
  return out.is_discarded() ? MessageParse::kNotJson : MessageParse::kOk;
}

}  // namespace bodyfmt::lsp
