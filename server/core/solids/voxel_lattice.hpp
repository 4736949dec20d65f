#pragma once
// A coarse tetrahedral lattice built around a closed fine surface, with the surface embedded in
// it: how the thesis turns a detailed model into something stable to simulate (thesis 2 §7.1).

#include "core/geometry/tet_mesh.hpp"
#include "core/geometry/triangle_mesh.hpp"
#include "core/solids/embedded_surface.hpp"

namespace felt {

/// A simulated lattice and the fine surface it carries.
struct EmbeddedSolid {
  TetMesh lattice;
  EmbeddedSurface surface;
};

/// The five-tetrahedra lattice (make_cell_lattice) of the cubic cells around `surface`:
/// `resolution` cells along the longest side of its bounding box, the grid centred on the box.
/// A cell is kept when its centre is inside the surface (generalized winding number above ½,
/// which tolerates small holes and overlaps) or when it holds a surface vertex that no such cell
/// holds, so every fine vertex lies in the lattice. Cells are then added where kept cells meet
/// only along an edge or at a corner, so the lattice's surface is a closed manifold.
EmbeddedSolid voxelize_surface(const TriangleMesh& surface, int resolution);

}  // namespace felt
