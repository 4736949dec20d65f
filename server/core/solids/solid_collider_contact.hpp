#pragma once
// Soft-solid nodes against the static colliders of a scene, the floor plane y = 0 of thesis 2
// §4.1 among them (the thesis leaves open how floor contacts are resolved).

#include <cstddef>
#include <span>

#include "core/collision/collider.hpp"
#include "core/solids/solid_body.hpp"

namespace felt {

/// Projects every free node of `body` that lies inside a collider onto its surface, as a
/// correction of its position only (the previous position moves with it), then stops its
/// approach with a perfectly inelastic impulse: the velocity lives in x − x_prev
/// (SolidBody::finish_step), so the previous position is moved to leave no approaching normal
/// motion; the node neither bounces back in nor springs out, and a resting contact stays
/// still. Coulomb friction then takes back tangential motion over the step, at most μ times
/// the approach stopped, never reversing it, by moving the position, so a node that static
/// friction holds stays exactly where it was; μ mixes the collider's and the body's. Returns
/// how many contacts it resolved.
std::size_t resolve_collider_contacts(std::span<const Collider> colliders, SolidBody& body);

}  // namespace felt
