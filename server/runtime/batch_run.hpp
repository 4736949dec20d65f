#pragma once
// Stepping a scene headless, as fast as it goes: `feltd run`, tests and benchmarks.

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "device/haptic_recording.hpp"
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
  int substeps = 1;         ///< of its last step (World::step_counts)
  std::uint64_t rescued_steps = 0;
  std::uint64_t over_budget_steps = 0;
};

/// Where a system's steps spent their time over a run, stage by stage.
struct StageRunStats {
  int max_substeps = 0;
  StepProfile mean;  ///< per step
  StepProfile max;   ///< the slowest step of each stage
};

/// The soft-solid pipeline over a run, as the second thesis's Tables 7.3 and 7.4 report it.
struct SolidRunStats : StageRunStats {
  double mean_colliding_nodes = 0;
  std::size_t max_colliding_nodes = 0;
  double mean_colliding_triangles = 0;
  std::size_t max_colliding_triangles = 0;
};

/// The scripted haptic devices over a run: timings like thesis 1 Table 9.4, the force's
/// smoothness in contact (its vibration), and, when replaying, collision equivalence.
struct HapticRunStats {
  std::uint64_t ticks = 0;
  std::uint64_t contact_ticks = 0;  ///< ticks where some device touched something
  double mean_contact_us = 0;       ///< mean time of a tick with contact ("CD")
  double mean_free_us = 0;          ///< and without ("N-CD")
  double max_force = 0;             ///< N, over every device and tick
  /// N: the largest and the mean change of a device's force from one tick to the next while it
  /// stays in contact
  double max_force_step = 0;
  double mean_force_step = 0;
  std::uint64_t compared = 0;    ///< replay: records compared
  std::uint64_t equivalent = 0;  ///< replay: of those, collision-equivalent
};

/// What a batch run does with the scene's scripted devices besides ticking them.
struct BatchHaptics {
  std::ostream* record = nullptr;  ///< every tick's records go here (CSV)
  /// replay: the devices follow these records' positions instead of their scripts, and each
  /// tick is compared with the record it replays
  const std::vector<HapticRecord>* replay = nullptr;
  Real tolerance = 1e-6;  ///< m, for collision equivalence
};

struct BatchRunStats {
  std::uint64_t steps = 0;
  double sim_time = 0;
  double wall_seconds = 0;
  /// CPU time of the stepping thread over the same steps: the cost without what else the
  /// machine runs (on a shared machine wall time also counts the waits for a core)
  double cpu_seconds = 0;
  double ms_per_step = 0;
  bool nonfinite = false;  ///< a step could not be rescued, or a non-finite value remains
  std::uint64_t rescued_steps = 0;
  std::uint64_t unrecoverable_steps = 0;
  /// steps some body's budget cut short (StepFlag::kOverBudget)
  std::uint64_t over_budget_steps = 0;
  std::vector<BodyRunStats> bodies;
  StageRunStats cloth;
  SolidRunStats solids;
  HapticRunStats haptics;
};

/// Looks at the world after each step (a trace, a comparison with a reference run).
using StepObserver = std::function<void(const World& world, const StepReport& report)>;

/// Takes `steps` steps of `scene` and reports what happened. The scene's scripted devices are
/// ticked at the servo rate in simulated time, after each step, against the surfaces between
/// the last two steps (as the servo thread renders them live), so a run is reproducible.
/// `observer`, if given, is called after each step; its time is left out of the wall time, so
/// that what it records does not count as the cost of the simulation.
BatchRunStats run_batch(Scene& scene, std::uint64_t steps, const BatchHaptics& haptics = {},
                        const StepObserver& observer = {});

}  // namespace felt
