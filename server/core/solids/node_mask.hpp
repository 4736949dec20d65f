#pragma once
// Which nodes a partial force evaluation must get right: the deformation region of a contact
// (thesis 2 §3.3 i) re-evaluates the forces of a few nodes of a large body, and only the
// elements that act on those nodes need to be visited.

#include <array>
#include <cstdint>
#include <span>

namespace felt {

/// mask[n] != 0 selects node n; an empty mask selects every node.
using NodeMask = std::span<const std::uint8_t>;

/// Whether an element with corners `nodes` acts on a node `mask` selects.
template <std::size_t N>
bool acts_on_selected(NodeMask mask, const std::array<std::uint32_t, N>& nodes) {
  if (mask.empty()) return true;
  for (std::uint32_t n : nodes) {
    if (mask[n] != 0) return true;
  }
  return false;
}

}  // namespace felt
