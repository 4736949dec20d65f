#pragma once
// Stepping a scene headless, as fast as it goes: `feltd run`, tests and benchmarks.

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace felt {

struct BodyRunStats {
  std::string name;
  std::string kind;           ///< "cloth" or "solid"
  std::size_t particles = 0;  ///< a cloth's particles, a solid's lattice nodes
  std::size_t edges = 0;
  std::size_t triangles = 0;  ///< a cloth's triangles, a solid's lattice surface triangles
  std::size_t tets = 0;
  std::size_t fine_vertices = 0;  ///< a solid's embedded surface, if it has one
  std::size_t fine_triangles = 0;
  double kinetic_energy = 0;
  double max_strain = 0;    ///< cloth
  double volume_ratio = 1;  ///< solid: volume over rest volume
};

/// The soft-solid pipeline over a run, as the second thesis's Tables 7.3 and 7.4 report it.
struct SolidRunStats {
  double mean_colliding_nodes = 0;
  std::size_t max_colliding_nodes = 0;
  double mean_colliding_triangles = 0;
  std::size_t max_colliding_triangles = 0;
  int max_substeps = 0;
  SolidStageTimes mean_ms;  ///< per step, milliseconds
  SolidStageTimes max_ms;   ///< the slowest step of each stage
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
  SolidRunStats solids;
};

/// Takes `steps` steps of `scene` and reports what happened.
BatchRunStats run_batch(Scene& scene, std::uint64_t steps);

}  // namespace felt
