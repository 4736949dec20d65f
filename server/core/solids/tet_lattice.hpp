#pragma once
// Regular tetrahedral lattices: every cubic cell split into five tetrahedra, mirrored in
// alternate cells so the face diagonals of neighbouring cells match (thesis 2 §7.1). The
// thesis found irregular TetGen meshes unstable and simulated these instead.

#include <array>
#include <cstdint>
#include <functional>

#include "core/geometry/tet_mesh.hpp"

namespace felt {

/// A block of nx × ny × nz cells of size cell_size, its minimum corner at origin.
struct LatticeGrid {
  std::array<int, 3> cells = {1, 1, 1};
  Vec3 origin = Vec3::Zero();
  Vec3 cell_size = Vec3::Ones();

  Vec3 node_position(int i, int j, int k) const {
    return origin + Vec3(i, j, k).cwiseProduct(cell_size);
  }
};

/// The lattice of the cells for which keep(i, j, k) is true, with only the nodes they use,
/// numbered in x-fastest grid order. Tetrahedra come five per kept cell, in cell order.
TetMesh make_cell_lattice(const LatticeGrid& grid, const std::function<bool(int, int, int)>& keep);

/// The full box: (nx+1)(ny+1)(nz+1) nodes and 5·nx·ny·nz tetrahedra.
TetMesh make_box_lattice(const LatticeGrid& grid);

}  // namespace felt
