#pragma once
// What each body of a live scene is doing, for GetStats: how it is integrated and how far it is
// from its rest shape. Measured by the physics thread once per statistics window.

#include <string>
#include <vector>

#include "core/world/world.hpp"

namespace felt {

struct BodyStats {
  BodyId body_id = 0;
  std::string kind;        ///< "cloth" or "solid"
  std::string integrator;  ///< its name; a solid's model update when it has no integrator
  Real max_strain = 0;     ///< cloth: ClothBody::max_strain
  Real volume_ratio = 1;   ///< solid: volume / rest volume
  Real kinetic_energy = 0;
  int substeps = 1;  ///< of its last step (World::step_counts): its stable step's or a rescue's
  std::uint64_t rescued_steps = 0;
  Real max_compression = 0;             ///< cloth: ClothBody::max_compression
  std::uint64_t over_budget_steps = 0;  ///< World::step_counts
  Real max_step = 0;                    ///< s, its own longest step; 0 when it has none
};

/// Every cloth and solid of `world`, in id order.
std::vector<BodyStats> body_stats(const World& world);

}  // namespace felt
