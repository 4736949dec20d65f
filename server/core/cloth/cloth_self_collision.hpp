#pragma once
// Cloth against itself (thesis 1 lists self-collision as skipped): particles closer than the
// cloth's thickness to one of its own triangles are found by optimized spatial hashing
// (Teschner et al. 2003, thesis 1 §6) and pushed apart with an inelastic repulsion (Bridson et
// al. 2002).

#include <cstdint>
#include <span>
#include <vector>

#include "core/collision/spatial_hash.hpp"
#include "core/integrate/particle_state.hpp"

namespace felt {

/// A particle closer than the thickness to a triangle it is not a corner of.
struct SelfProximity {
  std::uint32_t particle = 0;
  std::uint32_t triangle = 0;

  friend bool operator==(const SelfProximity&, const SelfProximity&) = default;
};

/// Keeps its hash table and pair list between calls, so a step allocates nothing once sized.
/// One instance per cloth keeps the table's size stable.
class ClothSelfCollision {
 public:
  /// Every particle–triangle pair closer than `thickness`, a triangle's own corners excluded,
  /// ordered by triangle. Particles are hashed into cells of the mean edge length plus twice
  /// the thickness; each triangle's bounding box, grown by the thickness, is looked up. Valid
  /// until the next call.
  std::span<const SelfProximity> find_proximities(std::span<const Triangle> triangles,
                                                  std::span<const Vec3> x, Real thickness);

  /// Finds the pairs closer than `thickness` and pushes each apart along the direction from the
  /// triangle's nearest point to the particle (the face normal, on the side the particle comes
  /// from, when it lies on the triangle) until they are `thickness` apart; an approaching normal
  /// relative velocity is removed (inelastic). Both are shared between the particle and the
  /// triangle's corners by inverse mass and barycentric weight, so momentum is conserved and
  /// pinned particles never move. Pairs are taken in turn, each from the positions the ones
  /// before it left. Proximity only, not continuous: a particle that moves more than the
  /// thickness in one call's worth of time can pass through. Returns the pairs it moved.
  std::size_t resolve(std::span<const Triangle> triangles, std::span<const Real> inv_mass,
                      Real thickness, ParticleState& state);

 private:
  SpatialHash hash_;
  std::vector<SelfProximity> proximities_;
};

}  // namespace felt
