#include "felt_cloth.hpp"

#include <chrono>
#include <cmath>
#include <memory>

#include "core/cloth/cloth_grid.hpp"
#include "core/integrate/projective_dynamics.hpp"
#include "core/integrate/xpbd_integrator.hpp"
#include "core/math/check.hpp"
#include "core/world/world.hpp"

namespace felt::peers {

Outcome run_felt(std::uint32_t n, const FeltConfig& config) {
  GridClothSpec spec;
  spec.width = spec.height = kSide;
  spec.nx = spec.ny = n;
  spec.total_mass = kMass;
  ClothModel model = make_grid_cloth(spec);
  FELT_CHECK((model.rest_positions[n + 1] - rest_position(n, 1, 1)).norm() < 1e-12);
  ClothParams params;
  const Real k = config.stiffness;
  params.spring(SpringKind::kStructural) = {true, k, 0.05};
  params.spring(SpringKind::kShear) = {true, k / 4, 0.02};
  params.spring(SpringKind::kBend) = {true, k / 40, 0.005};
  params.drag = kDampingRate * kMass / (static_cast<Real>(n) * n);
  std::unique_ptr<Integrator> integrator =
      config.integrator == "xpbd" ? std::make_unique<XpbdIntegrator>(config.substeps)
      : config.iterations > 0
          ? std::make_unique<ProjectiveDynamics>(config.iterations, config.chebyshev_rho)
          : make_integrator(config.integrator);
  FELT_CHECK(integrator != nullptr);
  World world(WorldSettings{Vec3(0, -kGravity, 0), config.step});
  world.add_body(ClothBody("cloth", std::make_shared<const ClothModel>(std::move(model)), params,
                           std::move(integrator)));
  ClothBody& cloth = world.cloths()[0];
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) cloth.pin(p);

  const long steps = std::lround(kSeconds / config.step);
  StepFlags flags;
  const auto start = std::chrono::steady_clock::now();
  for (long s = 0; s < steps; ++s) flags |= world.step().flags;
  const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;

  const std::span<const Vec3> x = cloth.state().x;
  Outcome outcome;
  outcome.wall_per_sim_s = wall.count() / kSeconds;
  outcome.max_strain = max_structural_strain(n, x);
  outcome.sag_error = sag_error(x);
  outcome.ok = intact(outcome.max_strain, x) && !flags.has(StepFlag::kUnrecoverable);
  if (flags.has(StepFlag::kRescued)) outcome.note = "rescued";
  return outcome;
}

}  // namespace felt::peers
