#pragma once
// What the cursor is on in the outline: a key, or a scalar (or alias) and the entry it is the
// value of (through any lists: `rotation: [[1, 0, 0, 90]]`).

#include "outline.h"

#include <cstddef>

namespace bodyfmt::lsp {

struct AtCursor {
  int key_mapping = -1;               ///< the mapping whose key holds the cursor
  const OutlineEntry* key = nullptr;  ///< that key
  int value = -1;                     ///< the scalar or alias that holds the cursor
  int holder_mapping = -1;            ///< the mapping whose entry `holder` the value is under
  const OutlineEntry* holder = nullptr;
};

/// A key or value holds `offset` when offset is in [begin, end]: the cursor just after a word
/// is on it.
AtCursor locate(const Outline& outline, std::size_t offset);

/// The entry and mapping that node `node` is (inside) the value of: climbs out of lists.
const OutlineEntry* holder_of(const Outline& outline, int node, int& mapping);

}  // namespace bodyfmt::lsp
