#pragma once
// Cloth from any triangle mesh (thesis 1 could only build rectangles).

#include "core/cloth/cloth_model.hpp"
#include "core/geometry/triangle_mesh.hpp"

namespace felt {

/// Every mesh edge becomes a structural spring; every edge shared by two triangles also gets a
/// bend spring between the two vertices opposite it. Masses are lumped by area (each triangle
/// gives a third of its area to each corner) and scaled to `total_mass`, so an irregular mesh
/// has no heavy spots where it is finely triangulated. Vertices no triangle uses get the mean
/// mass, so none is massless.
ClothModel make_mesh_cloth(const TriangleMesh& mesh, Real total_mass);

}  // namespace felt
