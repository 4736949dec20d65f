#pragma once
// The full simulated state of a world — its clock and every body's motion and pins — taken out
// and put back (a scene's save and restore). What a body is (its mesh, material, parameters)
// is not part of it: a state goes back into the bodies it was taken from.

#include <cstdint>
#include <expected>
#include <string>
#include <vector>

#include "core/world/world.hpp"

namespace felt {

struct BodyMotionState {
  BodyId body_id = 0;
  std::vector<Vec3> positions;  ///< a cloth's particles, a solid's lattice nodes
  std::vector<Vec3> velocities;
  std::vector<Vec3> previous_positions;  ///< solids (position Verlet); empty for a cloth
  Real previous_step = 0;                ///< solids: the length of the last step
  std::vector<std::uint32_t> pinned;
};

struct WorldState {
  std::uint64_t step = 0;
  std::vector<BodyMotionState> bodies;  ///< cloths and solids; colliders have no state
};

WorldState capture_state(const World& world);

/// Puts `state` back into `world`: every body it names must be live with the same number of
/// particles, every value finite and every position and velocity within ±kMaxVectorComponent
/// (core/math/bounds.hpp); otherwise nothing changes and the error says what is
/// wrong. Bodies it does not name keep their state. Integrators forget what they keep between
/// steps (as after a rollback), so stateless integrators continue bit for bit.
std::expected<void, std::string> restore_state(World& world, const WorldState& state);

}  // namespace felt
