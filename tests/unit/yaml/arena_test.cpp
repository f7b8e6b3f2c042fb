#include "yaml/arena.h"

#include <doctest/doctest.h>

#include <cstdint>

using bodyfmt::yaml::Arena;

TEST_CASE("yaml arena: allocations are aligned and a rewind hands the same memory out again") {
  Arena arena;
  void* first = arena.allocate(3, 1);
  void* aligned = arena.allocate(16, 8);
  CHECK(reinterpret_cast<std::uintptr_t>(aligned) % 8 == 0);
  CHECK(aligned != first);
  const Arena::Mark mark = arena.mark();
  void* item = arena.allocate(100, 8);
  arena.allocate(10'000, 8);  // past the first block
  arena.rewind(mark);
  CHECK(arena.allocate(100, 8) == item);
  // A request larger than any block gets a block of its own, and still reuses after a rewind.
  const Arena::Mark before_large = arena.mark();
  char* large = static_cast<char*>(arena.allocate(5u << 20, 16));
  large[(5u << 20) - 1] = 'x';
  arena.rewind(before_large);
  CHECK(static_cast<char*>(arena.allocate(5u << 20, 16)) == large);
}
