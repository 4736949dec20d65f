// Cost of the soft-solid pipeline at contact on the second thesis's scenes: a whole scene step
// (with its stage profile as counters, thesis 2 Table 7.4) and each stage of a substep on its
// own, from the state of most contact in the first 0.3 s after its bodies first touch.

#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <benchmark/benchmark.h>

#include "thesis_scenes.hpp"

namespace felt {
namespace {

/// A scene at contact: its solids' state after the step with the most colliding nodes within
/// the first 0.3 s (30 steps) after two bodies first touched.
struct SceneAtContact {
  Scene scene;
  std::vector<SolidBody::StepState> state;

  void restore() {
    std::vector<SolidBody>& bodies = scene.world.solids().bodies();
    for (std::size_t b = 0; b < bodies.size(); ++b) bodies[b].restore_step_state(state[b]);
  }
};

SceneAtContact bring_into_contact(std::string_view name) {
  constexpr int kMaxSteps = 2000, kWindow = 30;
  SceneAtContact at{bench::load_thesis_scene(name), {}};
  World& world = at.scene.world;
  std::vector<SolidBody>& bodies = world.solids().bodies();
  at.state.resize(bodies.size());
  int first_contact = -1;
  std::size_t most = 0;
  for (int step = 0; step < kMaxSteps && (first_contact < 0 || step < first_contact + kWindow);
       ++step) {
    world.step();
    const std::size_t colliding = world.solids().last_stats().colliding_nodes;
    if (colliding > 0 && first_contact < 0) first_contact = step;
    if (colliding > most) {
      most = colliding;
      for (std::size_t b = 0; b < bodies.size(); ++b) bodies[b].save_step_state(at.state[b]);
    }
  }
  if (first_contact < 0) throw std::runtime_error(std::string(name) + ": no contact");
  at.restore();
  return at;
}

/// Each scene is brought into contact once; every benchmark starts from that state.
SceneAtContact& scene_at_contact(std::string_view name) {
  static std::map<std::string, SceneAtContact, std::less<>> scenes;
  auto found = scenes.find(name);
  if (found == scenes.end()) found = scenes.emplace(name, bring_into_contact(name)).first;
  found->second.restore();
  return found->second;
}

// A whole scene step, the stages it spent its time in as counters (ms per step). The scene is
// put back at contact every 50 steps, before it comes to rest or slides apart.
void scene_step(benchmark::State& state, std::string_view name) {
  constexpr int kStepsFromContact = 50;
  SceneAtContact& at = scene_at_contact(name);
  World& world = at.scene.world;
  StepProfile total;
  double substeps = 0, colliding_nodes = 0;
  int since_contact = 0;
  for (auto _ : state) {
    if (++since_contact == kStepsFromContact) {
      state.PauseTiming();
      at.restore();
      since_contact = 0;
      state.ResumeTiming();
    }
    world.step();
    const SolidStepStats& stats = world.solids().last_stats();
    for (StepStage stage : bench::kStages) {
      total[stage] += stats.profile[stage];
    }
    substeps += stats.substeps;
    colliding_nodes += static_cast<double>(stats.colliding_nodes);
  }
  const auto per_step = [](double sum) {
    return benchmark::Counter(sum, benchmark::Counter::kAvgIterations);
  };
  for (StepStage stage : bench::kStages) {
    state.counters[std::string(stage_name(stage)) + "_ms"] = per_step(1e3 * total[stage]);
  }
  state.counters["substeps"] = per_step(substeps);
  state.counters["colliding_nodes"] = per_step(colliding_nodes);
}

enum class Stage { kIntegration, kDetection, kTriangles, kPenetration, kResolution };

// One stage of one substep, on the state a substep of the scene at contact reaches after its
// integration; the stages before it run once untimed.
void stage(benchmark::State& state, std::string_view name, Stage which) {
  SceneAtContact& at = scene_at_contact(name);
  World& world = at.scene.world;
  SolidSystem& solids = world.solids();
  std::vector<SolidBody>& bodies = solids.bodies();
  const SolidStepSettings& settings = solids.settings();
  const Real h = world.settings().time_step / std::max(1, solids.last_stats().substeps);
  const Vec3 gravity = world.settings().gravity;

  const auto advance = [&] {
    for (SolidBody& body : bodies) body.advance(h, gravity);
  };
  advance();
  std::vector<SolidBody::StepState> advanced(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) bodies[b].save_step_state(advanced[b]);

  SolidCollisionDetector detector;
  detector.set_cell_size(mean_rest_edge_length(bodies));
  PenetrationDepthEstimator penetration;
  ContactSurface surface;
  CollisionSet collisions;
  std::vector<PenetrationContact> contacts;
  // once untimed: the inputs of the timed stage, and the estimator's caches warm as in a run
  detector.detect(bodies, collisions);
  detector.collect_triangles(bodies, collisions);
  penetration.compute(bodies, collisions, settings.min_depth, contacts);

  for (auto _ : state) {
    switch (which) {
      case Stage::kIntegration:
        state.PauseTiming();
        at.restore();
        state.ResumeTiming();
        advance();
        break;
      case Stage::kDetection:
        detector.detect(bodies, collisions);
        break;
      case Stage::kTriangles:
        detector.collect_triangles(bodies, collisions);
        break;
      case Stage::kPenetration:
        penetration.compute(bodies, collisions, settings.min_depth, contacts);
        break;
      case Stage::kResolution:
        state.PauseTiming();
        for (std::size_t b = 0; b < bodies.size(); ++b) bodies[b].restore_step_state(advanced[b]);
        state.ResumeTiming();
        surface.resolve(bodies, contacts, settings.contact_iterations, settings.friction, h,
                        gravity);
        break;
    }
    benchmark::ClobberMemory();
  }
  state.counters["colliding_nodes"] = static_cast<double>(collisions.nodes.size());
}

#define FELT_SOLID_BENCHMARKS(scene)                                           \
  BENCHMARK_CAPTURE(scene_step, scene, #scene)->Unit(benchmark::kMicrosecond); \
  BENCHMARK_CAPTURE(stage, scene##_integration, #scene, Stage::kIntegration)   \
      ->Unit(benchmark::kMicrosecond);                                         \
  BENCHMARK_CAPTURE(stage, scene##_detection, #scene, Stage::kDetection)       \
      ->Unit(benchmark::kMicrosecond);                                         \
  BENCHMARK_CAPTURE(stage, scene##_triangles, #scene, Stage::kTriangles)       \
      ->Unit(benchmark::kMicrosecond);                                         \
  BENCHMARK_CAPTURE(stage, scene##_penetration, #scene, Stage::kPenetration)   \
      ->Unit(benchmark::kMicrosecond);                                         \
  BENCHMARK_CAPTURE(stage, scene##_resolution, #scene, Stage::kResolution)     \
      ->Unit(benchmark::kMicrosecond)

FELT_SOLID_BENCHMARKS(three_cubes);
FELT_SOLID_BENCHMARKS(four_bunnies);
FELT_SOLID_BENCHMARKS(cube_on_rings);
FELT_SOLID_BENCHMARKS(two_rings);

}  // namespace
}  // namespace felt
