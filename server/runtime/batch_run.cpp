#include "runtime/batch_run.hpp"

#include <algorithm>
#include <chrono>

#include "core/mesh_topology.hpp"

namespace felt {
namespace {

bool all_finite(std::span<const Vec3> values) {
  return std::ranges::all_of(values, [](const Vec3& v) { return v.allFinite(); });
}

/// Applies `op(total, step)` to each stage of two stage-time records.
template <typename Op>
void each_stage(SolidStageTimes& total, const SolidStageTimes& step, Op op) {
  op(total.integration, step.integration);
  op(total.detection, step.detection);
  op(total.triangles, step.triangles);
  op(total.penetration, step.penetration);
  op(total.resolution, step.resolution);
  op(total.colliders, step.colliders);
  op(total.finish, step.finish);
}

void record_solid_step(const SolidStepStats& step, SolidRunStats& run) {
  run.mean_colliding_nodes += static_cast<double>(step.colliding_nodes);
  run.mean_colliding_triangles += static_cast<double>(step.colliding_triangles);
  run.max_colliding_nodes = std::max(run.max_colliding_nodes, step.colliding_nodes);
  run.max_colliding_triangles = std::max(run.max_colliding_triangles, step.colliding_triangles);
  run.max_substeps = std::max(run.max_substeps, step.substeps);
  each_stage(run.mean_ms, step.times, [](Real& total, Real s) { total += 1e3 * s; });
  each_stage(run.max_ms, step.times, [](Real& worst, Real s) { worst = std::max(worst, 1e3 * s); });
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
  if (const EmbeddedSurface* fine = body.embedded_surface()) {
    stats.fine_vertices = fine->vertex_count();
    stats.fine_triangles = fine->triangles.size();
  }
  stats.kinetic_energy = body.kinetic_energy();
  stats.volume_ratio = body.volume() / body.rest_volume();
  return stats;
}

}  // namespace

BatchRunStats run_batch(Scene& scene, std::uint64_t steps) {
  BatchRunStats stats;
  World& world = scene.world;
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t s = 0; s < steps; ++s) {
    const StepReport report = world.step();
    if (report.flags & kStepRescued) ++stats.rescued_steps;
    if (report.flags & kStepUnrecoverable) ++stats.unrecoverable_steps;
    if (!world.solids().bodies().empty()) {
      record_solid_step(world.solids().last_stats(), stats.solids);
    }
  }
  stats.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.steps = steps;
  stats.sim_time = world.time();
  stats.ms_per_step = steps ? 1e3 * stats.wall_seconds / static_cast<double>(steps) : 0;
  if (steps > 0) {
    const double n = static_cast<double>(steps);
    stats.solids.mean_colliding_nodes /= n;
    stats.solids.mean_colliding_triangles /= n;
    each_stage(stats.solids.mean_ms, stats.solids.mean_ms, [n](Real& total, Real) { total /= n; });
  }
  stats.nonfinite = stats.unrecoverable_steps > 0;
  for (std::uint32_t id = 0; id < world.body_count(); ++id) {
    const BodyRef& ref = world.body_ref(id);
    if (ref.kind == BodyRef::Kind::kCloth) {
      const ClothBody& body = world.cloths()[ref.index];
      stats.nonfinite =
          stats.nonfinite || !all_finite(body.state().x) || !all_finite(body.state().v);
      stats.bodies.push_back(cloth_stats(body));
    } else {
      const SolidBody& body = world.solids().bodies()[ref.index];
      stats.nonfinite =
          stats.nonfinite || !all_finite(body.positions()) || !all_finite(body.velocities());
      stats.bodies.push_back(solid_stats(body));
    }
  }
  return stats;
}

}  // namespace felt
