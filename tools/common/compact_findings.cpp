#include "compact_findings.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace bodyfmt::tools {

namespace {
// Large enough that a block holds thousands of messages, small enough that the last one of a
// run with few findings wastes little (its pages are touched only as they fill).
constexpr std::size_t kBlockBytes = std::size_t{1} << 20;
}  // namespace

std::uint16_t CompactFindings::intern(std::vector<std::string>& table, const std::string& value) {
  // Few distinct values; a run repeats the last one most of the time.
  for (std::size_t i = table.size(); i-- > 0;)
    if (table[i] == value) return static_cast<std::uint16_t>(i);
  if (table.size() > UINT16_MAX) throw std::length_error("too many distinct rule ids");
  table.push_back(value);
  return static_cast<std::uint16_t>(table.size() - 1);
}

namespace {

void put_varint(std::string& out, std::size_t value) {
  for (; value >= 0x80; value >>= 7) out.push_back(static_cast<char>((value & 0x7f) | 0x80));
  out.push_back(static_cast<char>(value));
}

std::size_t get_varint(const char*& p) {
  std::size_t value = 0;
  for (int shift = 0;; shift += 7) {
    const auto byte = static_cast<unsigned char>(*p++);
    value |= static_cast<std::size_t>(byte & 0x7f) << shift;
    if (!(byte & 0x80)) return value;
  }
}

}  // namespace

void CompactFindings::append(std::string_view bytes) {
  std::memcpy(blocks_.back().get() + used_in_last_block_, bytes.data(), bytes.size());
  used_in_last_block_ += bytes.size();
}

CompactFindings::Text CompactFindings::store(std::uint16_t rule, std::string_view message) {
  std::string& previous = last_message_of_rule_[rule];
  std::size_t prefix = 0;
  const std::size_t common = std::min(previous.size(), message.size());
  while (prefix < common && previous[prefix] == message[prefix]) ++prefix;
  std::size_t suffix = 0;
  while (suffix < common - prefix && previous[previous.size() - 1 - suffix] == message[message.size() - 1 - suffix])
    ++suffix;
  std::string lengths;
  put_varint(lengths, prefix);
  put_varint(lengths, suffix);
  const std::string_view middle = message.substr(prefix, message.size() - prefix - suffix);
  const std::size_t size = lengths.size() + middle.size();
  if (blocks_.empty() || used_in_last_block_ + size > kBlockBytes) {
    blocks_.emplace_back(new char[std::max(kBlockBytes, size)]);  // not zeroed: pages are touched as they fill
    used_in_last_block_ = 0;
  }
  const Text stored{static_cast<std::uint32_t>(blocks_.size() - 1), static_cast<std::uint32_t>(used_in_last_block_),
                    static_cast<std::uint32_t>(size)};
  append(lengths);
  append(middle);
  previous.assign(message);
  return stored;
}

std::uint32_t CompactFindings::keep_hint(std::uint16_t rule, std::string&& hint) {
  if (hint.empty()) return 0;
  auto last = last_hint_of_rule_.find(rule);
  if (last != last_hint_of_rule_.end() && hints_[last->second] == hint) return last->second;
  hints_.push_back(std::move(hint));
  const auto index = static_cast<std::uint32_t>(hints_.size() - 1);
  last_hint_of_rule_[rule] = index;
  return index;
}

void CompactFindings::report(Diagnostic diagnostic) {
  const std::uint16_t rule = intern(rules_, diagnostic.rule_id);
  std::int32_t rare = -1;
  if (diagnostic.via || !diagnostic.fixes.empty()) {
    rare = static_cast<std::int32_t>(rare_.size());
    rare_.push_back(Rare{diagnostic.via, std::move(diagnostic.fixes)});
  }
  records_.push_back(Record{diagnostic.location, store(rule, diagnostic.message),
                            keep_hint(rule, std::move(diagnostic.fix_hint)), rule,
                            intern(categories_, diagnostic.category), diagnostic.severity, rare});
}

std::vector<Diagnostic> CompactFindings::take() {
  std::vector<Diagnostic> all;
  all.reserve(records_.size());
  std::size_t freed = 0;  // blocks before this one are freed
  std::map<std::uint16_t, std::string> previous_of_rule;
  for (; !records_.empty(); records_.pop_front()) {
    const Record& r = records_.front();
    // Messages are stored in arrival order, so a block behind this message is done with.
    for (; freed < r.message.block; ++freed) blocks_[freed].reset();
    const char* p = blocks_[r.message.block].get() + r.message.offset;
    const char* end = p + r.message.size;
    const std::size_t prefix = get_varint(p);
    const std::size_t suffix = get_varint(p);
    std::string& previous = previous_of_rule[r.rule];
    std::string message;
    message.reserve(prefix + static_cast<std::size_t>(end - p) + suffix);
    message.append(previous, 0, prefix).append(p, end).append(previous, previous.size() - suffix, suffix);
    previous = message;
    Rare none;
    Rare& rare = r.rare >= 0 ? rare_[static_cast<std::size_t>(r.rare)] : none;
    // The finding as it was made (by make_diagnostic), severity included.
    Diagnostic d{r.severity, rules_[r.rule], std::move(message),      r.location,
                 rare.via,   hints_[r.hint], categories_[r.category], std::move(rare.fixes)};
    all.push_back(std::move(d));
  }
  blocks_.clear();
  used_in_last_block_ = 0;
  last_message_of_rule_.clear();
  rare_.clear();
  hints_.resize(1);
  last_hint_of_rule_.clear();
  return all;
}

}  // namespace bodyfmt::tools
