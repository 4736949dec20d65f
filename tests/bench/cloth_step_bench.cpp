// Cost of one world step of an n × n hanging cloth, per integrator (the cloth sizes of thesis 1
// chapter 9, and 100 × 100), health checks included, and of the scene the service benchmark
// serves.

#include <benchmark/benchmark.h>

#include "bench_scene.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

World hanging_cloth(std::uint32_t n, std::string_view integrator) {
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
  // small step so every size stays stable with the explicit schemes
  World world(WorldSettings{Vec3(0, -9.81, 0), 2.5e-4, 100, 6});
  world.add_body(std::move(body));
  return world;
}

void step(benchmark::State& state, std::string_view integrator) {
  const auto n = static_cast<std::uint32_t>(state.range(0));
  World world = hanging_cloth(n, integrator);
  for (auto _ : state) {
    world.step();
    benchmark::ClobberMemory();
  }
  state.counters["particles"] = n * n;
  state.counters["triangles"] = 2.0 * (n - 1) * (n - 1);
}

// schemes that are stable on this cloth at h = 0.25 ms (explicit Euler is not: its failed
// steps would be retried with substeps and the benchmark would time the rescue)
BENCHMARK_CAPTURE(step, symplectic_euler, "symplectic_euler")
    ->Arg(10)
    ->Arg(20)
    ->Arg(40)
    ->Arg(50)
    ->Arg(100);
BENCHMARK_CAPTURE(step, verlet, "verlet")->Arg(10)->Arg(20)->Arg(40)->Arg(50)->Arg(100);
BENCHMARK_CAPTURE(step, rk4, "rk4")->Arg(10)->Arg(20)->Arg(40)->Arg(50)->Arg(100);
BENCHMARK_CAPTURE(step, implicit_euler, "implicit_euler")
    ->Arg(10)
    ->Arg(20)
    ->Arg(40)
    ->Arg(50)
    ->Arg(100);

// the scene docs/results/service.md serves: 100 x 100, symplectic Euler at 2 ms, stretch
// limited; touched by `range(0)` proxies, the balls (2 cm) its clients hold 1 cm in front of it
void served_scene(benchmark::State& state) {
  World world = bench::load_bench_scene("service_bench.json").world;
  for (int n = 0; n < 500; ++n) world.step();  // into its swing, as the service measures it
  std::vector<Collider> proxies;
  for (int c = 0; c < state.range(0); ++c) {
    Collider ball;
    ball.shape = Collider::Shape::kSphere;
    ball.center = Vec3(0.01 * c, 1.5, 0.01);
    ball.radius = 0.02;
    proxies.push_back(ball);
  }
  for (auto _ : state) {
    world.set_moving_colliders(proxies);  // a step uses them once, as the runtime's are
    world.step();
    benchmark::ClobberMemory();
  }
}
BENCHMARK(served_scene)->Arg(0)->Arg(8);

}  // namespace
}  // namespace felt
