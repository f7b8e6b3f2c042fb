#pragma once
// Reads the keys of one mapping node: looks up a key under its modern and legacy spellings,
// remembers what was consumed, and reports what was left over (body-format-spec §1, §14).

#include "load/load_context.h"

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace bodyfmt::detail {

/// Spellings of one key: the modern snake_case name first, then legacy spellings. The reader
/// keeps the views, so they must outlive it (string literals do).
using KeyNames = std::initializer_list<std::string_view>;

class MappingReader {
 public:
  MappingReader(LoadContext& ctx, const yaml::NodeRef& mapping, std::string what);

  /// The first present spelling, marked as consumed. A legacy spelling gets a
  /// `load-legacy-key` warning naming the modern key.
  yaml::NodeRef take(KeyNames names);
  bool has(KeyNames names) const;
  /// Marks a key as known without reading it (anchor hosts, keys read elsewhere).
  void ignore(std::string_view name);

  /// Reports every key that was neither taken nor ignored. A key close to one of `known`
  /// (edit distance) is a probable typo: `load-unknown-key` warning with a did-you-mean hint.
  /// A second spelling of a key read under another (`jointType` beside `joint_type`):
  /// `load-key-written-twice`. Other keys are kept as info by Choreonoid: `load-info-key` note.
  void report_unknown(const std::vector<std::string_view>& known);
  /// The same; the list is copied only when there is something to report.
  void report_unknown(std::initializer_list<std::string_view> known) {
    if (has_unknown()) report_unknown(std::vector<std::string_view>(known));
  }

  const yaml::NodeRef& node() const { return mapping_; }
  const std::string& what() const { return what_; }
  LoadContext& context() { return ctx_; }

 private:
  /// No candidate other than a spelling of `guess` is as close to `key`.
  bool unique_guess(std::string_view key, const std::vector<std::string_view>& candidates,
                    std::string_view guess) const;
  /// A key of the mapping was neither taken nor ignored (nor merged).
  bool has_unknown() const;
  /// `load-key-written-twice` for `entry`, a spelling of `modern` left because another
  /// spelling of it was read.
  void report_second_spelling(const yaml::MapEntry& entry, std::string_view modern);
  /// A legacy spelling of `modern` is a key of the mapping.
  bool has_spelling_of(std::string_view modern) const;

  /// The modern spelling of a legacy one seen by take(), or "" when `name` is none.
  std::string_view modern_of(std::string_view name) const;
  void consume(const yaml::MapEntry* entry);
  /// The mapping's entry `key`; most of a link's forty spellings are absent, and the filter
  /// rules nearly all of those out without a scan of the entries. Inline: take() calls it
  /// once per spelling.
  const yaml::MapEntry* find(std::string_view key) const {
    return (key_filter_ & filter_bit(key)) != 0 ? mapping_->find(key) : nullptr;
  }
  static std::uint64_t filter_bit(std::string_view key) {
    if (key.empty()) return 0;
    const auto first = static_cast<unsigned char>(key.front());
    const auto last = static_cast<unsigned char>(key.back());
    return std::uint64_t{1} << ((key.size() * 7 + first + last * 3) & 63);
  }

  // A link's mapping is read with some forty take() calls: the bookkeeping is flat.
  LoadContext& ctx_;
  yaml::NodeRef mapping_;
  std::string what_;
  std::uint64_t key_filter_ = 0;  ///< filter_bit of every key of the mapping
  // Which entries were taken or ignored: a bit each, inline for the mappings of up to 64 keys
  // that models are made of (three or four per link), so that reading one allocates nothing.
  static constexpr std::size_t kInlineEntries = 64;
  bool consumed(std::size_t i) const {
    return consumed_large_.empty() ? ((consumed_small_ >> i) & 1U) != 0 : consumed_large_[i];
  }
  std::uint64_t consumed_small_ = 0;
  std::vector<bool> consumed_large_;  ///< instead, for a mapping of more than kInlineEntries keys
  std::vector<std::pair<std::string_view, std::string_view>> legacy_;  ///< legacy spelling, modern
};

/// Whole-scalar reads of an optional key (body-format-spec §1.2): nullopt when the key is
/// absent, or when its value does not parse (warned, so the caller keeps its default).
std::optional<double> take_optional_double(MappingReader& r, KeyNames names);
std::optional<bool> take_optional_bool(MappingReader& r, KeyNames names);
/// take_optional_double of an angle, converted to radians (LoadContext::angle).
std::optional<double> take_optional_angle(MappingReader& r, KeyNames names);

template <typename T>
void assign_if(T& target, const std::optional<T>& value) {
  if (value) target = *value;
}

}  // namespace bodyfmt::detail
