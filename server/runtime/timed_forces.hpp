#pragma once
// Forces clients put on bodies for a while (ApplyForce), re-applied before every step until
// they expire. Owned by the physics thread.

#include <cstdint>
#include <vector>

#include "core/world/world.hpp"

namespace felt {

class TimedForces {
 public:
  /// `force` on each of `vertices` (of what clients see of `body`) for the steps that start
  /// before `until` (simulated seconds); at least the next step.
  void add(BodyId body, std::vector<std::uint32_t> vertices, const Vec3& force, Real until);

  /// Adds the live forces to `world` for the step starting now and drops the expired ones and
  /// those of bodies that are gone.
  void apply(World& world);

  void clear() { forces_.clear(); }
  std::size_t size() const { return forces_.size(); }

 private:
  struct Entry {
    BodyId body = 0;
    std::vector<std::uint32_t> vertices;
    Vec3 force = Vec3::Zero();
    Real until = 0;
    bool applied = false;  ///< once applied, it ends when `until` has passed
  };
  std::vector<Entry> forces_;
};

}  // namespace felt
