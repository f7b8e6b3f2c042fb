#include "text/text_util.h"

#include <algorithm>
#include <array>
#include <cstdio>

namespace bodyfmt::text {

int edit_distance(std::string_view a_text, std::string_view b_text) {
  // Optimal string alignment: insertions, deletions, substitutions and transpositions of two
  // adjacent characters each cost 1, case-insensitively (`jointRnage` is 1 from `jointRange`).
  // Case is folded for ASCII letters only (what std::tolower does in the "C" locale the tools
  // run in), once per string rather than per comparison: an unknown key is compared with every
  // known one, and tolower() calls were 3% of bodycheck's time on SR1.
  auto lowered = [](std::string_view text) {
    std::string out(text);
    for (char& c : out)
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
  };
  const std::string a = lowered(a_text);
  const std::string b = lowered(b_text);
  const std::size_t n = b.size();
  std::vector<int> before(n + 1), previous(n + 1), current(n + 1);
  for (std::size_t j = 0; j <= n; ++j) previous[j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = static_cast<int>(i);
    for (std::size_t j = 1; j <= n; ++j) {
      int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        current[j] = std::min(current[j], before[j - 2] + 1);
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[n];
}

std::string_view suggest(std::string_view word, const std::vector<std::string_view>& candidates) {
  std::string_view best;
  int best_distance = 1 << 30;
  for (std::string_view candidate : candidates) {
    int d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  // A typo changes a few characters of a long-enough word; short words are too ambiguous.
  int allowed = word.size() >= 8 ? 2 : (word.size() >= 4 ? 1 : 0);
  return best_distance <= allowed ? best : std::string_view{};
}

std::vector<std::string_view> nearest(std::string_view word, const std::vector<std::string_view>& candidates) {
  std::vector<std::string_view> best;
  int best_distance = word.size() >= 8 ? 2 : (word.size() >= 4 ? 1 : 0);  // as suggest()
  for (std::string_view candidate : candidates) {
    const int d = edit_distance(word, candidate);
    if (d > best_distance) continue;
    if (d < best_distance) best.clear();
    best_distance = d;
    best.push_back(candidate);
  }
  return best;
}

std::optional<bool> parse_bool_word(std::string_view word) {
  static constexpr std::array<std::string_view, 11> kTrue = {"y",    "Y",    "yes", "Yes", "YES", "true",
                                                             "True", "TRUE", "on",  "On",  "ON"};
  static constexpr std::array<std::string_view, 11> kFalse = {"n",     "N",     "no",  "No",  "NO", "false",
                                                              "False", "FALSE", "off", "Off", "OFF"};
  if (std::find(kTrue.begin(), kTrue.end(), word) != kTrue.end()) return true;
  if (std::find(kFalse.begin(), kFalse.end(), word) != kFalse.end()) return false;
  return std::nullopt;
}

std::vector<std::string_view> line_views(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    pos = end + 1;
  }
  return lines;
}

std::vector<std::string> split_lines(std::string_view text) {
  const std::vector<std::string_view> views = line_views(text);
  return std::vector<std::string>(views.begin(), views.end());
}

void append_one_line(std::string& out, std::string_view text) {
  static const char kHex[] = "0123456789abcdef";
  std::size_t plain = 0;  // text[plain, i) is copied as it is
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t length = 1;
    const char* escape = nullptr;
    char hex[7] = "\\x";
    if (c == '\n') {
      escape = "\\n";
    } else if (c == '\r') {
      escape = "\\r";
    } else if ((c < 0x20 && c != '\t') || c == 0x7F) {
      hex[2] = kHex[c >> 4], hex[3] = kHex[c & 0xF], hex[4] = 0;
      escape = hex;
    } else if (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
               static_cast<unsigned char>(text[i + 1]) <= 0x9F) {  // U+0080..U+009F
      const auto code = static_cast<unsigned char>(text[i + 1]);
      std::snprintf(hex, sizeof hex, "\\u%04x", code);
      escape = hex, length = 2;
    } else if (c == 0xE2 && i + 2 < text.size() && static_cast<unsigned char>(text[i + 1]) == 0x80 &&
               (text[i + 2] == '\xA8' || text[i + 2] == '\xA9')) {  // U+2028, U+2029
      escape = text[i + 2] == '\xA8' ? "\\u2028" : "\\u2029", length = 3;
    }
    if (!escape) continue;
    out.append(text.substr(plain, i - plain));
    out += escape;
    i += length - 1;
    plain = i + 1;
  }
  out.append(text.substr(plain));
}

}  // namespace bodyfmt::text
