// Wall seconds per simulated second against the final max strain for xpbd and symplectic Euler
// on the cloth of issue 29: 1 m × 1 m, 0.2 kg, hung by its two top corners, 2 s simulated,
// spring stiffness k (shear k/4, bend k/40) with the scenes' default damping. Prints a
// markdown table (docs/results/xpbd.md). Usage: xpbd_study [ROUNDS]; the configurations run
// in turn, ROUNDS times (default 3), and the table gives each one's median wall time.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/cloth/cloth_grid.hpp"
#include "core/integrate/xpbd_integrator.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

struct Config {
  std::uint32_t n;  ///< particles per side
  std::string integrator;
  Real k;        ///< structural stiffness, N/m
  Real h;        ///< world step, s
  int substeps;  ///< xpbd only
};

struct Result {
  Real wall_per_sim_s;
  Real max_strain;
  StepFlags flags;
};

Result run(const Config& c) {
  GridClothSpec spec;
  spec.nx = spec.ny = c.n;
  spec.total_mass = 0.2;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, c.k, 0.05};
  params.spring(SpringKind::kShear) = {true, c.k / 4, 0.02};
  params.spring(SpringKind::kBend) = {true, c.k / 40, 0.005};
  params.drag = 0.005;
  auto integrator = c.integrator == "xpbd" ? std::make_unique<XpbdIntegrator>(c.substeps)
                                           : make_integrator(c.integrator);
  World world(WorldSettings{Vec3(0, -9.81, 0), c.h, 100, 6});
  world.add_body(ClothBody("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                           std::move(integrator)));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) {
    world.cloths()[0].pin(p);
  }
  const Real seconds = 2;
  const long steps = std::lround(seconds / c.h);
  StepFlags flags;
  const auto start = std::chrono::steady_clock::now();
  for (long s = 0; s < steps; ++s) flags |= world.step().flags;
  const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
  return {wall.count() / seconds, world.cloths()[0].max_strain(), flags};
}

}  // namespace
}  // namespace felt

int main(int argc, char** argv) {
  using felt::Config;
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 3;
  const std::vector<Config> configs = {
      {40, "symplectic_euler", 250, 4.5e-4, 1},  {40, "symplectic_euler", 4000, 1.1e-4, 1},
      {40, "xpbd", 250, 1.0 / 240, 4},           {40, "xpbd", 250, 1.0 / 240, 8},
      {40, "xpbd", 250, 1.0 / 240, 16},          {40, "xpbd", 4000, 1.0 / 240, 8},
      {40, "xpbd", 4000, 1.0 / 240, 16},         {40, "xpbd", 4000, 1.0 / 240, 32},
      {100, "symplectic_euler", 600, 1.1e-4, 1}, {100, "xpbd", 600, 1.0 / 240, 8},
      {100, "xpbd", 600, 1.0 / 240, 16},         {100, "xpbd", 600, 1.0 / 240, 32},
  };
  std::vector<std::vector<felt::Result>> results(configs.size());
  for (int r = 0; r < rounds; ++r) {
    for (std::size_t i = 0; i < configs.size(); ++i) {
      results[i].push_back(felt::run(configs[i]));
      std::fprintf(stderr, "round %d config %zu: %.3f s/s\n", r, i,
                   results[i].back().wall_per_sim_s);
    }
  }
  std::printf(
      "| cloth | integrator | k (N/m) | step (ms) | substeps | h_s (ms) | wall s per "
      "simulated s (median of %d) | final max strain | flags "
      "|\n|---|---|---|---|---|---|---|---|---|\n",
      rounds);
  for (std::size_t i = 0; i < configs.size(); ++i) {
    std::vector<felt::Result>& r = results[i];
    std::sort(r.begin(), r.end(), [](const felt::Result& a, const felt::Result& b) {
      return a.wall_per_sim_s < b.wall_per_sim_s;
    });
    const Config& c = configs[i];
    std::printf("| %u × %u | %s | %g | %.3g | %d | %.3g | %.3f | %.4f | %s |\n", c.n, c.n,
                c.integrator.c_str(), c.k, c.h * 1e3, c.substeps, c.h / c.substeps * 1e3,
                r[r.size() / 2].wall_per_sim_s, r[r.size() / 2].max_strain,
                r[r.size() / 2].flags.ok()
                    ? "ok"
                    : (r[r.size() / 2].flags.has(felt::StepFlag::kUnrecoverable) ? "unrecoverable"
                                                                                 : "rescued"));
  }
  return 0;
}
