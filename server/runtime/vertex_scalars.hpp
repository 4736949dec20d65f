#pragma once
// The per-vertex scalar frames carry when a client asks for it (SubscribeFrames.scalars): how
// far a body is from its rest shape where each vertex is, for clients to colour.

#include <vector>

#include "runtime/snapshot.hpp"

namespace felt {

/// One value per vertex of `body`: a cloth's strain (vertex_strain), a solid's volume change
/// (node_volume_change, carried to an embedded surface's vertices by their barycentric
/// coordinates).
void vertex_scalars(const BodySnapshot& body, std::vector<float>& out);

}  // namespace felt
