#pragma once
// The links of an outline: each link mapping of `links` with its name and parent values,
// which go to definition, references, rename, completion and symbols share.

#include "outline.h"

#include <string>
#include <vector>

namespace bodyfmt::lsp {

struct LinkItem {
  int mapping = -1;
  int name = -1;    ///< the scalar node of `name`, or -1
  int parent = -1;  ///< the scalar node of `parent`, or -1
  std::string name_text;
  std::string parent_text;
};

/// In file order: the items of a `links` list, or the values of a `links` mapping.
std::vector<LinkItem> link_items(const Outline& outline);

}  // namespace bodyfmt::lsp
