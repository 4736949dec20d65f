// Cost of one world step of an n × n hanging cloth, per integrator (the cloth sizes of thesis 1
// chapter 9, and 100 × 100), health checks included, and of the scene the service benchmark
// serves. Each cloth steps at 0.25 ms or at its stable step, whichever is shorter (the light
// particles of a 100 × 100 cloth make symplectic Euler's limit shorter than 0.25 ms), and every
// row prints its step, the substeps the health check needed and the kinetic energy it ended
// with, so that no row times a cloth that blew up or was rescued.

#include <benchmark/benchmark.h>

#include <algorithm>

#include "bench_scene.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/cloth/cloth_stable_step.hpp"
#include "core/cloth/hanging_cloth.hpp"
#include "core/integrate/implicit_euler.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

constexpr Real kLongestStep = 2.5e-4;  ///< s

ClothBody hanging_cloth(std::uint32_t n, std::string_view integrator) {
  GridClothSpec spec;
  spec.nx = spec.ny = n;
  spec.total_mass = 0.5;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 200, 0.05};
  params.spring(SpringKind::kShear) = {true, 50, 0.02};
  params.spring(SpringKind::kBend) = {true, 5, 0.005};
  params.drag = 0.005;
  ClothBody body("cloth", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 make_integrator(integrator));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) body.pin(p);
  return body;
}

void step(benchmark::State& state, std::string_view integrator) {
  const auto n = static_cast<std::uint32_t>(state.range(0));
  ClothBody body = hanging_cloth(n, integrator);
  const Real h = std::min(kLongestStep, stable_cloth_step(body));
  if (h <= 0) {
    state.SkipWithError("no step is stable for this integrator on this cloth");
    return;
  }
  World world(WorldSettings{Vec3(0, -9.81, 0), h, 100, 6});
  world.add_body(std::move(body));
  int substeps = 1;
  std::int64_t rescued = 0;
  // implicit Euler's conjugate-gradient iterations (issue 29, item 3)
  const auto* implicit = dynamic_cast<const ImplicitEuler*>(&world.cloths()[0].integrator());
  std::int64_t iterations = 0;
  for (auto _ : state) {
    const StepReport report = world.step();
    substeps = std::max(substeps, report.max_substeps);
    rescued += report.flags.has(StepFlag::kRescued) ? 1 : 0;
    if (implicit) iterations += implicit->last_solve().iterations;
    benchmark::ClobberMemory();
  }
  if (implicit) {
    state.counters["cg_iterations"] =
        static_cast<double>(iterations) / static_cast<double>(state.iterations());
  }
  const ClothBody& cloth = world.cloths()[0];
  state.counters["particles"] = n * n;
  state.counters["h_ms"] = 1e3 * h;
  state.counters["substeps"] = substeps;
  state.counters["rescued"] = static_cast<double>(rescued);
  state.counters["sim_s"] = world.time();
  state.counters["KE_end_J"] = cloth.kinetic_energy();
  state.counters["strain_end"] = cloth.max_strain();
}

void cloth_sizes(benchmark::internal::Benchmark* b) {
  for (const int n : {10, 20, 40, 50, 100}) b->Arg(n);
}
BENCHMARK_CAPTURE(step, symplectic_euler, "symplectic_euler")->Apply(cloth_sizes);
BENCHMARK_CAPTURE(step, explicit_euler, "explicit_euler")->Apply(cloth_sizes);
BENCHMARK_CAPTURE(step, verlet, "verlet")->Apply(cloth_sizes);
BENCHMARK_CAPTURE(step, rk4, "rk4")->Apply(cloth_sizes);
BENCHMARK_CAPTURE(step, implicit_euler, "implicit_euler")->Apply(cloth_sizes);
BENCHMARK_CAPTURE(step, imex, "imex")->Apply(cloth_sizes);
BENCHMARK_CAPTURE(step, kang, "kang")->Apply(cloth_sizes);
BENCHMARK_CAPTURE(step, xpbd, "xpbd")->Apply(cloth_sizes);
BENCHMARK_CAPTURE(step, projective_dynamics, "projective_dynamics")->Apply(cloth_sizes);

// the scene docs/results/service.md serves: 100 x 100, kang at 2 ms, stretch limited; touched by
// `range(0)` proxies, the balls (2 cm) its clients hold 1 cm in front of it
void served_scene(benchmark::State& state) {
  World world = bench::load_bench_scene("service_bench.json").world;
  for (int n = 0; n < 500; ++n) world.step();  // into its swing, as the service measures it
  const std::vector<Collider> proxies =
      test::balls_in_a_row(static_cast<int>(state.range(0)), Vec3(0, 1.5, 0.01), 0.01, 0.02);
  for (auto _ : state) {
    world.set_moving_colliders(proxies);  // a step uses them once, as the runtime's are
    world.step();
    benchmark::ClobberMemory();
  }
}
BENCHMARK(served_scene)->Arg(0)->Arg(8);

}  // namespace
}  // namespace felt
