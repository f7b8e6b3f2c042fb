#include "text_positions.h"

#include <algorithm>

namespace bodyfmt::lsp {

std::size_t utf8_sequence_length(std::string_view text, std::size_t i, int* utf16_units) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 1;
  unsigned minimum = 0;
  unsigned code = lead;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2, code = lead & 0x1F, minimum = 0x80;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3, code = lead & 0x0F, minimum = 0x800;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4, code = lead & 0x07, minimum = 0x10000;
  }
  if (length > 1) {
    bool valid = i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      valid = (byte(i + k) & 0xC0) == 0x80;
      code = (code << 6) | (byte(i + k) & 0x3F);
    }
    // Overlong forms, surrogates and code points above U+10FFFF are invalid bytes too.
    if (!valid || code < minimum || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF) {
      length = 1;
    } else {
      if (utf16_units) *utf16_units = length == 4 ? 2 : 1;
      return length;
    }
  }
  if (utf16_units) *utf16_units = 1;
  return length;
}

TextLines::TextLines(std::string_view text) : text_(text) {
  starts_.push_back(0);
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
    if (text[i] == '\n' || text[i] == '\r') starts_.push_back(i + 1);
  }
}

std::size_t TextLines::line_start(int line) const {
  if (line < 0) return 0;
  if (line >= line_count()) return text_.size();
  return starts_[static_cast<std::size_t>(line)];
}

std::string_view TextLines::line(int line) const {
  if (line < 0 || line >= line_count()) return {};
  const std::size_t begin = starts_[static_cast<std::size_t>(line)];
  std::size_t end = line + 1 < line_count() ? starts_[static_cast<std::size_t>(line) + 1] : text_.size();
  while (end > begin && (text_[end - 1] == '\n' || text_[end - 1] == '\r')) --end;
  return text_.substr(begin, end - begin);
}

std::size_t TextLines::offset_of(Utf16Position position) const {
  if (position.line < 0) return 0;
  if (position.line >= line_count()) return text_.size();
  const std::string_view text = line(position.line);
  const std::size_t begin = line_start(position.line);
  std::size_t i = 0;
  int units = 0;
  while (i < text.size()) {
    int n = 0;
    const std::size_t length = utf8_sequence_length(text, i, &n);
    if (units + n > position.character) break;
    units += n;
    i += length;
  }
  return begin + i;
}

Utf16Position TextLines::position_of(std::size_t offset) const {
  offset = std::min(offset, text_.size());
  const auto after = std::upper_bound(starts_.begin(), starts_.end(), offset);
  const int index = static_cast<int>(after - starts_.begin()) - 1;
  const std::string_view text = line(index);
  const std::size_t target = std::min(offset - starts_[static_cast<std::size_t>(index)], text.size());
  int units = 0;
  for (std::size_t i = 0; i < target;) {
    int n = 0;
    const std::size_t length = utf8_sequence_length(text, i, &n);
    if (i + length > target) break;  // inside a character: its start
    units += n;
    i += length;
  }
  return {index, units};
}

std::size_t TextLines::offset_of_column(int line, int column) const {
  if (line < 1) return 0;
  if (line > line_count()) return text_.size();
  const std::size_t begin = line_start(line - 1);
  const std::size_t length = this->line(line - 1).size();
  return begin + std::min<std::size_t>(column > 0 ? static_cast<std::size_t>(column - 1) : 0, length);
}

Utf16Range TextLines::token_range(int line, int column) const {
  const std::size_t begin = offset_of_column(line, column);
  const int index = std::clamp(line - 1, 0, std::max(line_count() - 1, 0));
  const std::string_view text = this->line(index);
  const std::size_t line_begin = line_start(index);
  std::size_t i = begin >= line_begin ? begin - line_begin : 0;
  std::size_t end = i;
  if (i < text.size() && (text[i] == '"' || text[i] == '\'')) {
    const char quote = text[i];
    end = i + 1;
    while (end < text.size() && text[end] != quote) end += text[end] == '\\' && quote == '"' ? 2 : 1;
    end = std::min(end + 1, text.size());
  } else {
    while (end < text.size()) {
      const char c = text[end];
      if (c == ',' || c == ']' || c == '}' || c == '[' || c == '{') break;
      if (c == ':' && (end + 1 == text.size() || text[end + 1] == ' ' || text[end + 1] == '\t')) break;
      if (c == '#' && end > i && (text[end - 1] == ' ' || text[end - 1] == '\t')) break;
      ++end;
    }
    while (end > i && (text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
  }
  if (end == i && i < text.size()) end = i + utf8_sequence_length(text, i, nullptr);
  return {position_of(line_begin + i), position_of(line_begin + end)};
}

void apply_change(std::string& text, Utf16Range range, std::string_view replacement) {
  const TextLines lines(text);
  std::size_t begin = lines.offset_of(range.start);
  std::size_t end = lines.offset_of(range.end);
  if (end < begin) std::swap(begin, end);
  text.replace(begin, end - begin, replacement);
}

}  // namespace bodyfmt::lsp
