#pragma once
// Stepping a scene headless, as fast as it goes: `feltd run`, tests and benchmarks.

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace felt {

struct BodyRunStats {
  std::string name;
  std::size_t particles = 0;
  std::size_t edges = 0;
  std::size_t triangles = 0;
  std::size_t tets = 0;
  double kinetic_energy = 0;
  double max_strain = 0;
};

struct BatchRunStats {
  std::uint64_t steps = 0;
  double sim_time = 0;
  double wall_seconds = 0;
  double ms_per_step = 0;
  bool nonfinite = false;  ///< a step could not be rescued, or a non-finite value remains
  std::uint64_t rescued_steps = 0;
  std::uint64_t unrecoverable_steps = 0;
  std::vector<BodyRunStats> bodies;
};

/// Takes `steps` steps of `scene` and reports what happened.
BatchRunStats run_batch(Scene& scene, std::uint64_t steps);

}  // namespace felt
