#pragma once
// How far a body's surface moves between the physics snapshots a haptic proxy renders
// against: per snapshot pair, the largest move of any vertex, and along a chain of pairs (each
// pair's older snapshot the previous pair's newer one) the sum of those, a bound on how far any
// vertex moved from the start of the chain. Whoever publishes the snapshots keeps it (the
// runtime's haptic frames; tests and benchmarks that move a surface by hand), and the
// god-object bounds from it how far to look for what moved onto its path (surface_carry.hpp).

#include <cstdint>
#include <span>

#include "core/math/types.hpp"

namespace felt {

struct SurfaceMotion {
  Real max_displacement = 0;  ///< the largest distance a vertex moves from `from` to `to`
  /// a bound on how far a vertex has moved from the start of the chain to `to`: the sum of the
  /// pairs' max_displacement. Two surfaces' bounds subtract when they are on the same chain.
  Real travelled = 0;
  std::uint64_t chain = 0;  ///< names the chain; 0: on none

  /// The motion of the next pair on this chain, whose vertices move from `from` to `to` (the
  /// same vertices, as many). A new chain starts from SurfaceMotion{0, 0, its name}.
  SurfaceMotion then(std::span<const Vec3> from, std::span<const Vec3> to) const;
  /// The motion of the next pair on this chain, whose farthest vertex moves `displacement`.
  SurfaceMotion moved(Real displacement) const {
    return {displacement, travelled + displacement, chain};
  }
};

}  // namespace felt
