#pragma once
// Closed triangle surfaces made from parameters: the fine models of the thesis's scenes (the
// cube and the rings of thesis 2 Table 7.1) and a sphere. All are centred at the origin, their
// triangles counter-clockwise seen from outside, each vertex with one texture coordinate (the
// vertices are shared, so the texture wraps across one seam).

#include "core/geometry/triangle_mesh.hpp"

namespace felt {

/// A torus around the y axis: the tube of radius `minor_radius` follows the circle of radius
/// `major_radius` in the xz plane. major_segments × minor_segments vertices, twice as many
/// triangles; u runs around the y axis, v around the tube.
TriangleMesh make_torus_surface(Real major_radius, Real minor_radius, int major_segments,
                                int minor_segments);

/// An icosphere: the icosahedron with every triangle split into four `subdivisions` times, its
/// vertices pushed onto the sphere. 10·4ⁿ + 2 vertices, 20·4ⁿ triangles, none degenerate; uv
/// is longitude and latitude.
TriangleMesh make_sphere_surface(Real radius, int subdivisions);

/// The surface of a box of the given size, every face a grid of divisions × divisions
/// rectangles split into two triangles: 6n² + 2 vertices, 12n² triangles (n = 20 is the
/// thesis's fine cube: 2402 and 4800). uv is the longitude and latitude of the direction from
/// the centre.
TriangleMesh make_box_surface(const Vec3& size, int divisions);

}  // namespace felt
