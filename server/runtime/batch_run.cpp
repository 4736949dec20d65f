#include "runtime/batch_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include <utility>

#include "core/geometry/mesh_topology.hpp"
#include "core/math/all_finite.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/reaction_accumulator.hpp"
#include "runtime/scripted_devices.hpp"
#include "scheduling/thread_cpu_time.hpp"

namespace felt {
namespace {

/// Adds one step's profile to a run's: the sums (divided by the steps at the end) and maxima.
void record_stages(const StepProfile& step, int substeps, StageRunStats& run) {
  run.max_substeps = std::max(run.max_substeps, substeps);
  for (std::size_t s = 0; s < kStepStageCount; ++s) {
    run.mean.seconds[s] += step.seconds[s];
    run.max.seconds[s] = std::max(run.max.seconds[s], step.seconds[s]);
  }
}

void record_solid_step(const SolidStepStats& step, SolidRunStats& run) {
  run.mean_colliding_nodes += static_cast<double>(step.colliding_nodes);
  run.mean_colliding_triangles += static_cast<double>(step.colliding_triangles);
  run.max_colliding_nodes = std::max(run.max_colliding_nodes, step.colliding_nodes);
  run.max_colliding_triangles = std::max(run.max_colliding_triangles, step.colliding_triangles);
  record_stages(step.profile, step.substeps, run);
}

BodyRunStats cloth_stats(const ClothBody& body) {
  BodyRunStats stats;
  stats.name = body.name();
  stats.kind = "cloth";
  stats.particles = body.model().particle_count();
  stats.edges = unique_edge_count(body.model().triangles);
  stats.triangles = body.model().triangles.size();
  stats.kinetic_energy = body.kinetic_energy();
  stats.max_strain = body.max_strain();
  return stats;
}

BodyRunStats solid_stats(const SolidBody& body) {
  BodyRunStats stats;
  stats.name = body.name();
  stats.kind = "solid";
  stats.particles = body.node_count();
  stats.edges = body.topology().edges.size();
  stats.triangles = body.topology().surface.size();
  stats.tets = body.rest().tets.size();
  if (const EmbeddedSurface* fine = body.embedded_surface(); fine && !fine->lattice_own) {
    stats.fine_vertices = fine->vertex_count();
    stats.fine_triangles = fine->triangles.size();
  }
  stats.kinetic_energy = body.kinetic_energy();
  stats.volume_ratio = body.volume() / body.rest_volume();
  return stats;
}

/// The scene's scripted devices ticked between steps in simulated time.
class BatchServo {
 public:
  BatchServo(const Scene& scene, const BatchHaptics& options)
      : options_(options),
        devices_(options.replay ? devices_from_recording(*options.replay) : scene.devices,
                 scene.haptics),
        kind_(scene.haptic_structure),
        ticks_per_step_(std::max<std::uint64_t>(
            1, static_cast<std::uint64_t>(
                   std::llround(scene.world.settings().time_step * scene.servo_rate)))),
        last_forces_(devices_.size()),
        was_touching_(devices_.size(), false) {
    if (options.record) devices_.record_to(options.record);
  }

  bool empty() const { return devices_.empty(); }

  void before_step(World& world) { reactions_.apply_and_clear(world); }

  /// Ticks the devices through the step that just ended at `world.time()`.
  void after_step(const World& world, HapticRunStats& stats) {
    snapshot_ = make_snapshot(world, snapshot_.get());
    // two frames take turns: the older one is refitted into the newer
    auto frame =
        make_haptic_frame(snapshot_, frame_.get(), std::move(spare_), kind_, SteadyClock::now());
    spare_ = std::exchange(frame_, std::move(frame));
    const Real h = world.settings().time_step;
    const Real start = world.time() - h;
    const Real dt = h / static_cast<Real>(ticks_per_step_);
    for (std::uint64_t k = 1; k <= ticks_per_step_; ++k) {
      const auto tick_start = std::chrono::steady_clock::now();
      devices_.tick(frame_->surface_at(static_cast<Real>(k) / ticks_per_step_),
                    start + static_cast<Real>(k) * dt, dt, reactions_);
      const double us =
          1e6 *
          std::chrono::duration<double>(std::chrono::steady_clock::now() - tick_start).count();
      record_tick(us, stats);
    }
  }

 private:
  void record_tick(double us, HapticRunStats& stats) {
    ++stats.ticks;
    bool touching = false;
    const auto& latest = devices_.latest();
    for (std::size_t d = 0; d < latest.size(); ++d) {
      const HapticRecord& r = latest[d];
      touching = touching || r.in_contact;
      stats.max_force = std::max(stats.max_force, r.force.norm());
      if (r.in_contact && was_touching_[d]) {
        const double change = (r.force - last_forces_[d]).norm();
        stats.max_force_step = std::max(stats.max_force_step, change);
        stats.mean_force_step += change;
        ++force_steps_;
      }
      was_touching_[d] = r.in_contact;
      last_forces_[d] = r.force;
      if (options_.replay && replayed_ < options_.replay->size()) {
        ++stats.compared;
        stats.equivalent +=
            collision_equivalent((*options_.replay)[replayed_++], r, options_.tolerance) ? 1 : 0;
      }
    }
    if (touching) {
      ++stats.contact_ticks;
      stats.mean_contact_us += us;
    } else {
      stats.mean_free_us += us;
    }
  }

 public:
  void finish(HapticRunStats& stats) const {
    if (stats.contact_ticks) stats.mean_contact_us /= static_cast<double>(stats.contact_ticks);
    if (stats.ticks > stats.contact_ticks) {
      stats.mean_free_us /= static_cast<double>(stats.ticks - stats.contact_ticks);
    }
    if (force_steps_) stats.mean_force_step /= static_cast<double>(force_steps_);
  }

 private:
  const BatchHaptics& options_;
  ScriptedDevices devices_;
  TriangleQueryKind kind_;
  std::uint64_t ticks_per_step_;
  ReactionAccumulator reactions_;
  std::shared_ptr<const SceneSnapshot> snapshot_;
  std::shared_ptr<HapticFrame> frame_, spare_;
  std::vector<Vec3> last_forces_;
  std::vector<bool> was_touching_;
  std::uint64_t force_steps_ = 0;
  std::size_t replayed_ = 0;
};

}  // namespace

BatchRunStats run_batch(Scene& scene, std::uint64_t steps, const BatchHaptics& haptics,
                        const StepObserver& observer) {
  BatchRunStats stats;
  World& world = scene.world;
  std::optional<BatchServo> servo;
  if (!scene.devices.empty() || haptics.replay) servo.emplace(scene, haptics);
  const auto start = std::chrono::steady_clock::now();
  std::chrono::steady_clock::duration observed{};
  const double cpu_start = thread_cpu_seconds();
  double cpu_observed = 0;
  for (std::uint64_t s = 0; s < steps; ++s) {
    if (servo) servo->before_step(world);
    const StepReport report = world.step();
    if (servo) servo->after_step(world, stats.haptics);
    if (report.flags.has(StepFlag::kRescued)) ++stats.rescued_steps;
    if (report.flags.has(StepFlag::kUnrecoverable)) ++stats.unrecoverable_steps;
    if (report.flags.has(StepFlag::kOverBudget)) ++stats.over_budget_steps;
    if (!world.cloth_system().bodies().empty()) {
      record_stages(report.cloth_profile, world.cloth_system().last_stats().substeps, stats.cloth);
    }
    if (!std::as_const(world).solids().bodies().empty()) {
      record_solid_step(std::as_const(world).solids().last_stats(), stats.solids);
    }
    if (observer) {
      const auto observe_start = std::chrono::steady_clock::now();
      const double cpu_observe_start = thread_cpu_seconds();
      observer(world, report);
      observed += std::chrono::steady_clock::now() - observe_start;
      cpu_observed += thread_cpu_seconds() - cpu_observe_start;
    }
  }
  stats.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start - observed).count();
  stats.cpu_seconds = thread_cpu_seconds() - cpu_start - cpu_observed;
  if (servo) servo->finish(stats.haptics);
  stats.steps = steps;
  stats.sim_time = world.time();
  stats.ms_per_step = steps ? 1e3 * stats.wall_seconds / static_cast<double>(steps) : 0;
  if (steps > 0) {
    const double n = static_cast<double>(steps);
    stats.solids.mean_colliding_nodes /= n;
    stats.solids.mean_colliding_triangles /= n;
    for (StepProfile* mean : {&stats.cloth.mean, &stats.solids.mean}) {
      for (Real& seconds : mean->seconds) seconds /= n;
    }
  }
  stats.nonfinite = stats.unrecoverable_steps > 0;
  for (BodyId id : world.body_ids()) {
    const BodyRef& ref = world.body_ref(id);
    if (ref.kind == BodyRef::Kind::kCollider) continue;
    if (ref.kind == BodyRef::Kind::kCloth) {
      const ClothBody& body = world.cloths()[ref.index];
      stats.nonfinite =
          stats.nonfinite || !all_finite(body.state().x) || !all_finite(body.state().v);
      stats.bodies.push_back(cloth_stats(body));
    } else {
      const SolidBody& body = std::as_const(world).solids().bodies()[ref.index];
      stats.nonfinite =
          stats.nonfinite || !all_finite(body.positions()) || !all_finite(body.velocities());
      stats.bodies.push_back(solid_stats(body));
    }
    BodyRunStats& body = stats.bodies.back();
    body.substeps = world.step_counts(id).substeps;
    body.rescued_steps = world.substeps(id).rescued_steps();
    body.over_budget_steps = world.step_counts(id).over_budget_steps;
  }
  return stats;
}

}  // namespace felt
