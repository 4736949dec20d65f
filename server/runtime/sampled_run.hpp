#pragma once
// A headless run looked at every so many steps (`feltd compare`, `feltd sweep`): what it cost,
// how its energy drifted and whether its steps held, with the caller measuring each sample.

#include <cstdint>
#include <functional>

#include "scene/scene.hpp"

namespace felt {

struct SampledRunStats {
  double time_step = 0;     ///< s
  double sim_time = 0;      ///< s, at the end
  double wall_seconds = 0;  ///< of the steps alone, not of the sampling
  double wall_per_sim_second = 0;
  double cpu_seconds = 0;  ///< of the stepping thread, over the same steps
  double cpu_per_sim_second = 0;
  Real start_energy = 0;      ///< J, kinetic + elastic + gravitational of every body
  Real energy_drift = 0;      ///< J, at the last sample against the start
  Real max_energy_drift = 0;  ///< J, the largest |E − E_start| over the samples
  std::uint64_t rescued_steps = 0;
  std::uint64_t unrecoverable_steps = 0;
  std::uint64_t over_budget_steps = 0;
  bool nonfinite = false;  ///< as BatchRunStats::nonfinite
};

/// Called with the world at sample `k` (0, 1, ...), after (k + 1) · steps_per_sample steps.
using SampleObserver = std::function<void(const World& world, std::size_t k)>;

/// Takes samples · steps_per_sample steps of `scene` (as run_batch does, scripted devices
/// included) and calls `observer` at each sample.
SampledRunStats run_sampled(Scene& scene, std::uint64_t steps_per_sample, std::size_t samples,
                            const SampleObserver& observer = {});

}  // namespace felt
