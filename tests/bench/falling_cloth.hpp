#pragma once
// The haptics benchmarks' deforming cloth: the default scene's springs on a side × side grid
// lying in the xz plane, pinned at the two corners of one edge, falling under gravity.

#include <cstdint>
#include <memory>

#include "core/cloth/cloth_grid.hpp"
#include "core/world/world.hpp"

namespace felt::bench {

/// A world holding that cloth, stepped by implicit Euler (stable at 1 ms up to 100 × 100) at
/// `time_step`, with viscous drag `drag` per particle.
inline World falling_cloth(std::uint32_t side, Real drag, Real time_step) {
  GridClothSpec spec;
  spec.nx = spec.ny = side;
  spec.total_mass = 0.5;
  spec.plane = GridClothSpec::Plane::kXZ;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 200, 0.05};
  params.spring(SpringKind::kShear) = {true, 50, 0.02};
  params.spring(SpringKind::kBend) = {true, 5, 0.005};
  params.drag = drag;
  ClothBody body("cloth", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 make_integrator("implicit_euler"));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) body.pin(p);
  World world(WorldSettings{Vec3(0, -9.81, 0), time_step, 100, 6, 2});
  world.add_body(std::move(body));
  return world;
}

}  // namespace felt::bench
