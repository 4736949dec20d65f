// Cost of one haptic proxy solve (brute force over all triangles) against a snapshot, with and
// without contact: the reference the acceleration structures of the haptics issue must beat
// (thesis 1 Table 9.4, column AD).

#include <benchmark/benchmark.h>

#include "core/cloth_grid.hpp"
#include "runtime/proxy_contact.hpp"

namespace felt {
namespace {

void solve(benchmark::State& state, bool in_contact) {
  const auto n = static_cast<std::uint32_t>(state.range(0));
  GridClothSpec spec;
  spec.nx = spec.ny = n;
  World world;
  world.add_body(ClothBody("cloth", std::make_shared<const ClothModel>(make_grid_cloth(spec)),
                           ClothParams{}, make_integrator("symplectic_euler")));
  const auto snapshot = make_snapshot(world);
  const ProxySettings settings{0.02, 400, 10};
  const Vec3 position = in_contact ? Vec3(0.01, 0.01, 0.01) : Vec3(0.01, 0.01, 0.5);
  for (auto _ : state) benchmark::DoNotOptimize(solve_proxy_contact(*snapshot, settings, position));
  state.counters["triangles"] = 2.0 * (n - 1) * (n - 1);
}

BENCHMARK_CAPTURE(solve, contact, true)->Arg(10)->Arg(20)->Arg(40)->Arg(50)->Arg(100);
BENCHMARK_CAPTURE(solve, free, false)->Arg(10)->Arg(20)->Arg(40)->Arg(50)->Arg(100);

}  // namespace
}  // namespace felt
