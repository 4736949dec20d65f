#pragma once
// How much a solid is squeezed or swollen at each lattice node, for clients to colour: the
// volume change V / V₀ − 1 of its tetrahedra, averaged over the tetrahedra at the node
// (the solid's counterpart of a cloth's vertex strain).

#include <span>
#include <vector>

#include "core/geometry/tet_mesh.hpp"

namespace felt {

/// One value per node of `rest` at positions `x` (0 where no tetrahedron meets; a tetrahedron
/// of no rest volume counts as unchanged).
void node_volume_change(const TetMesh& rest, std::span<const Vec3> x, std::vector<float>& out);

}  // namespace felt
