#pragma once
/// assimp's glTF2 exporter, and aiNode's destructor, recurse once per level of the node tree,
/// about 200 bytes of stack per level: a 50,000-link chain overflows the 8 MB main stack. The
/// export therefore runs on a thread whose stack is sized for the tree's depth (reserved
/// address space; only the pages used are backed by memory).
#include <cstddef>
#include <functional>

namespace bodyfmt::gltf {

/// The stack for a node tree `depth` levels deep: 64 MB plus 2 KB per level.
std::size_t stack_for_depth(std::size_t depth);

/// Runs `work` on a new thread with a stack of `bytes` and waits for it; an exception `work`
/// throws is rethrown here. Returns false (without running `work`) when no such thread can be
/// created.
bool run_with_stack(std::size_t bytes, const std::function<void()>& work);

}  // namespace bodyfmt::gltf
