#include "yaml/arena.h"

#include <algorithm>

namespace bodyfmt::yaml {

void* Arena::allocate_in_next_block(std::size_t size, std::size_t alignment) {
  // A free block after a rewind is reused when the request fits in it.
  if (current_ + 1 < blocks_.size() && size + alignment <= blocks_[current_ + 1].size) {
    ++current_;
    used_ = 0;
    return allocate(size, alignment);
  }
  const std::size_t previous = blocks_.empty() ? 0 : blocks_[current_].size;
  const std::size_t grown = std::clamp(previous * 2, kFirstBlock, kLargestBlock);
  Block block;
  block.size = std::max(grown, size + alignment);
  block.data.reset(new std::byte[block.size]);  // not zeroed: pages are touched as used
  const std::size_t at = blocks_.empty() ? 0 : current_ + 1;
  blocks_.insert(blocks_.begin() + static_cast<std::ptrdiff_t>(at), std::move(block));
  current_ = at;
  used_ = 0;
  return allocate(size, alignment);
}

void Arena::rewind(Mark position) {
  current_ = position.block;
  used_ = position.used;
}

}  // namespace bodyfmt::yaml
