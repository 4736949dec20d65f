#include "runtime/batch_run.hpp"

#include <chrono>

#include "core/mesh_topology.hpp"

namespace felt {
namespace {

bool all_finite(const ParticleState& state) {
  for (std::size_t p = 0; p < state.size(); ++p) {
    if (!state.x[p].allFinite() || !state.v[p].allFinite()) return false;
  }
  return true;
}

}  // namespace

BatchRunStats run_batch(Scene& scene, std::uint64_t steps) {
  BatchRunStats stats;
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t s = 0; s < steps; ++s) {
    const StepReport report = scene.world.step();
    if (report.flags & kStepRescued) ++stats.rescued_steps;
    if (report.flags & kStepUnrecoverable) ++stats.unrecoverable_steps;
  }
  stats.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.steps = steps;
  stats.sim_time = scene.world.time();
  stats.ms_per_step = steps ? 1e3 * stats.wall_seconds / static_cast<double>(steps) : 0;
  stats.nonfinite = stats.unrecoverable_steps > 0;
  for (const ClothBody& body : scene.world.bodies()) {
    stats.nonfinite = stats.nonfinite || !all_finite(body.state());
    stats.bodies.push_back(
        {body.name(), body.model().particle_count(), unique_edge_count(body.model().triangles),
         body.model().triangles.size(), 0, body.kinetic_energy(), body.max_strain()});
  }
  return stats;
}

}  // namespace felt
