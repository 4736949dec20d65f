#include "runtime/sampled_run.hpp"

#include <cmath>

#include "runtime/batch_run.hpp"
#include "runtime/body_measures.hpp"

namespace felt {

SampledRunStats run_sampled(Scene& scene, std::uint64_t steps_per_sample, std::size_t samples,
                            const SampleObserver& observer) {
  SampledRunStats out;
  out.time_step = scene.world.settings().time_step;
  out.start_energy = mechanical_energy(scene.world);
  std::size_t k = 0;
  const BatchRunStats batch =
      run_batch(scene, steps_per_sample * samples, {}, [&](const World& world, const StepReport&) {
        if (world.step_count() % steps_per_sample != 0) return;
        out.energy_drift = mechanical_energy(world) - out.start_energy;
        if (!(std::abs(out.energy_drift) <= out.max_energy_drift)) {
          out.max_energy_drift = std::abs(out.energy_drift);  // NaN wins
        }
        if (observer) observer(world, k);
        ++k;
      });
  out.sim_time = batch.sim_time;
  out.wall_seconds = batch.wall_seconds;
  out.wall_per_sim_second = batch.sim_time > 0 ? batch.wall_seconds / batch.sim_time : 0;
  out.cpu_seconds = batch.cpu_seconds;
  out.cpu_per_sim_second = batch.sim_time > 0 ? batch.cpu_seconds / batch.sim_time : 0;
  out.rescued_steps = batch.rescued_steps;
  out.unrecoverable_steps = batch.unrecoverable_steps;
  out.over_budget_steps = batch.over_budget_steps;
  out.nonfinite = batch.nonfinite;
  return out;
}

}  // namespace felt
