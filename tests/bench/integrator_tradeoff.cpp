// Prints the speed/accuracy trade of every integrator on one cloth as a Markdown table: the
// error of its final state against a reference solution, and the wall time per simulated
// second. Not a unit test: run it by hand (machines are noisy) and commit the table under
// docs/results/.
//
// The scene: a 15 × 15 cloth of 0.2 kg, 0.6 m wide, released horizontally with two corners
// pinned, so it swings down through large motions. Reference: RK4 at h = 10 µs.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/cloth_grid.hpp"
#include "core/world.hpp"

namespace felt {
namespace {

constexpr Real kSimTime = 0.5;

World swinging_cloth(std::string_view integrator, Real h) {
  GridClothSpec spec;
  spec.nx = spec.ny = 15;
  spec.width = spec.height = 0.6;
  spec.total_mass = 0.2;
  spec.plane = GridClothSpec::Plane::kXZ;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 150, 0.02};
  params.spring(SpringKind::kShear) = {true, 40, 0.01};
  params.spring(SpringKind::kBend) = {true, 2, 0.002};
  params.drag = 0.002;
  ClothBody body("cloth", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 make_integrator(integrator));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) body.pin(p);
  // no rescue: the table shows what each scheme does on its own
  World world(WorldSettings{Vec3(0, -9.81, 0), h, 1e3, 0, 1e300});
  world.add_body(std::move(body));
  return world;
}

struct Run {
  std::vector<Vec3> x;
  double wall_seconds = 0;
  bool failed = false;
};

Run run(std::string_view integrator, Real h) {
  World world = swinging_cloth(integrator, h);
  const auto steps = static_cast<long>(std::lround(kSimTime / h));
  const auto start = std::chrono::steady_clock::now();
  Run result;
  for (long n = 0; n < steps; ++n) {
    if (world.step().flags & kStepUnrecoverable) {
      result.failed = true;
      break;
    }
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.x = world.bodies()[0].state().x;
  return result;
}

}  // namespace
}  // namespace felt

int main() {
  using namespace felt;
  const Run reference = run("rk4", 1e-5);
  std::printf("| integrator | h (ms) | max error (mm) | wall ms per simulated s | stable |\n");
  std::printf("|---|---|---|---|---|\n");
  for (std::string_view name : integrator_names()) {
    for (const Real h : {2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4}) {
      const Run r = run(name, h);
      Real error = 0;
      for (std::size_t p = 0; p < r.x.size(); ++p)
        error = std::max(error, (r.x[p] - reference.x[p]).norm());
      const bool stable = !r.failed && std::isfinite(error) && error < 0.1;
      char error_text[32] = "—";
      if (stable) std::snprintf(error_text, sizeof error_text, "%.3g", error * 1e3);
      std::printf("| %s | %.2f | %s | %.1f | %s |\n", std::string(name).c_str(), h * 1e3,
                  error_text, 1e3 * r.wall_seconds / kSimTime, stable ? "yes" : "no");
    }
  }
  return 0;
}
