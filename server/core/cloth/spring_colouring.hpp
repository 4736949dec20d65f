#pragma once
// A graph colouring of a cloth's springs: classes in which no two springs share a particle.
// Projected class by class, the springs of a class are independent of each other (Gauss–Seidel
// between classes, Jacobi within one), as in Fratarcangeli, Tibaldo & Pellacini, "Vivace: a
// Practical Gauss-Seidel Method for Stable Soft Body Dynamics", SIGGRAPH Asia 2016.

#include <cstdint>
#include <span>
#include <vector>

#include "core/cloth/spring.hpp"

namespace felt {

struct SpringColouring {
  std::vector<std::uint32_t> order;       ///< spring indices, class by class
  std::vector<std::uint32_t> class_ends;  ///< class c is order[class_ends[c − 1], class_ends[c])

  std::size_t class_count() const { return class_ends.size(); }
};

/// Greedy colouring in the springs' order: each spring takes the lowest class none of its
/// particles' springs has yet, so there are at most 2Δ − 1 classes (Δ the most springs on one
/// particle), 13 for a grid with structural, shear and bend springs.
SpringColouring colour_springs(std::span<const Spring> springs, std::size_t particle_count);

}  // namespace felt
