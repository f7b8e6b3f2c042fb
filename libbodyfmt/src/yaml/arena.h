#pragma once
// The memory of one YAML document: a bump allocator whose position can be saved and restored.
// A reader that consumes a subtree while the document is still being parsed (the links of a
// 100,000-link file, ParseOptions::stream) hands the subtree's memory to the next one, so the
// tree never holds every link at once.

#include <cstddef>
#include <memory>
#include <vector>

namespace bodyfmt::yaml {

class Arena {
 public:
  /// A position: everything allocated after it can be released with rewind().
  struct Mark {
    std::size_t block = 0;
    std::size_t used = 0;
  };

  Arena() = default;
  Arena(const Arena&) = delete;
  Arena& operator=(const Arena&) = delete;

  void* allocate(std::size_t size, std::size_t alignment) {
    // Inline: a 100,000-link file makes millions of small allocations.
    if (current_ < blocks_.size()) {
      const std::size_t begin = (used_ + alignment - 1) / alignment * alignment;
      if (begin + size <= blocks_[current_].size) {
        used_ = begin + size;
        return blocks_[current_].data.get() + begin;
      }
    }
    return allocate_in_next_block(size, alignment);
  }
  Mark mark() const { return Mark{current_, used_}; }
  /// Releases everything allocated since `position` for reuse. Nothing is destroyed: the
  /// arena holds trivially destructible data only.
  void rewind(Mark position);

 private:
  void* allocate_in_next_block(std::size_t size, std::size_t alignment);

  struct Block {
    std::unique_ptr<std::byte[]> data;
    std::size_t size = 0;
  };
  // Blocks grow to a ceiling rather than doubling for ever: a half-empty last block of a
  // doubling series would be a quarter of a large document's memory.
  static constexpr std::size_t kFirstBlock = 4096;
  static constexpr std::size_t kLargestBlock = std::size_t{1} << 20;

  std::vector<Block> blocks_;  ///< blocks after current_ are free (after a rewind)
  std::size_t current_ = 0;
  std::size_t used_ = 0;  ///< bytes taken in blocks_[current_]
};

}  // namespace bodyfmt::yaml
