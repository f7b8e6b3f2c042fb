#pragma once
// The link names of a model with their link indices, looked up once per link while the tree
// is built (body-format-spec §5.2). Open addressing in one array of 8-byte slots, the names
// beside it in insertion order: a 100,000-link model makes no allocation per name, and a
// lookup compares a name only when its hash matches.

#include <bodyfmt/model.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

namespace bodyfmt::detail {

class NameIndex {
 public:
  explicit NameIndex(std::size_t expected = 0) {
    std::size_t capacity = 16;
    while (capacity < expected * 2) capacity *= 2;  // at most half full
    slots_.resize(capacity);
    names_.reserve(expected);
    indices_.reserve(expected);
  }

  /// Adds `name` (a view that must outlive the index) for link `index`. When the name is there
  /// already, nothing is added and the index it has is returned.
  std::optional<LinkIndex> insert(std::string_view name, LinkIndex index) {
    if ((names_.size() + 1) * 2 > slots_.size()) grow();
    const std::size_t hash = std::hash<std::string_view>()(name);
    Slot& slot = slots_[probe(name, hash)];
    if (slot.entry != kEmpty) return indices_[slot.entry];
    slot = Slot{tag_of(hash), static_cast<std::uint32_t>(names_.size())};
    names_.push_back(name);
    indices_.push_back(index);
    return std::nullopt;
  }

  std::optional<LinkIndex> find(std::string_view name) const {
    const Slot& slot = slots_[probe(name, std::hash<std::string_view>()(name))];
    if (slot.entry == kEmpty) return std::nullopt;
    return indices_[slot.entry];
  }

  /// The names, in the order they were added.
  const std::vector<std::string_view>& names() const { return names_; }

 private:
  static constexpr std::uint32_t kEmpty = UINT32_MAX;
  struct Slot {
    std::uint32_t tag = 0;  ///< high bits of the name's hash
    std::uint32_t entry = kEmpty;
  };
  static std::uint32_t tag_of(std::size_t hash) { return static_cast<std::uint32_t>(hash >> 32); }

  /// The slot holding `name`, or the empty slot where it belongs.
  std::size_t probe(std::string_view name, std::size_t hash) const {
    const std::size_t mask = slots_.size() - 1;
    const std::uint32_t tag = tag_of(hash);
    for (std::size_t i = hash & mask;; i = (i + 1) & mask) {
      const Slot& slot = slots_[i];
      if (slot.entry == kEmpty || (slot.tag == tag && names_[slot.entry] == name)) return i;
    }
  }

  void grow() {
    std::vector<Slot> old(slots_.size() * 2);
    old.swap(slots_);
    const std::size_t mask = slots_.size() - 1;
    for (const Slot& slot : old) {
      if (slot.entry == kEmpty) continue;
      std::size_t i = std::hash<std::string_view>()(names_[slot.entry]) & mask;
      while (slots_[i].entry != kEmpty) i = (i + 1) & mask;
      slots_[i] = slot;
    }
  }

  std::vector<Slot> slots_;  ///< a power of two
  std::vector<std::string_view> names_;
  std::vector<LinkIndex> indices_;
};

}  // namespace bodyfmt::detail
