#pragma once
// Lattice boxes placed anywhere, with the thesis's material, for the contact and pipeline tests.

#include <array>
#include <cstdint>

#include <gtest/gtest.h>

#include "core/solids/solid_fixtures.hpp"

namespace felt::test {

/// Appendix C's material: 50 g per node, k_D = 60, k_V = 20, d_C = 2.
inline SolidMaterial thesis_material() {
  return mass_spring(0.05, 60, 20, 2);
}

/// A lattice box of `cells` cells of size `cell` with its minimum corner at `origin`.
inline SolidBody box_body(std::array<int, 3> cells, const Vec3& cell, const Vec3& origin,
                          const SolidMaterial& material = thesis_material()) {
  LatticeGrid grid;
  grid.cells = cells;
  grid.cell_size = cell;
  grid.origin = origin;
  return SolidBody("box", make_box_lattice(grid), material);
}

/// The node of `body` at position p (a lattice corner), or fails the calling test.
inline std::uint32_t node_at(const SolidBody& body, const Vec3& p) {
  for (std::uint32_t n = 0; n < body.node_count(); ++n) {
    if ((body.positions()[n] - p).norm() < 1e-12) return n;
  }
  ADD_FAILURE() << "no node at " << p.transpose();
  return 0;
}

}  // namespace felt::test
