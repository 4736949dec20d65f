#pragma once
// The served benchmark scene's cloth (2 m, 4 kg, structural / shear / bend 30 / 8 / 1 N/m) hung
// by its pins, its sag, and balls to press into it: shared by the stretch-limiter tests and the
// stretch-limit study.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/cloth/cloth_grid.hpp"
#include "core/collision/collider.hpp"
#include "core/world/world.hpp"

namespace felt::test {

/// That cloth at n × n, centred at (0, 1.5, 0), its springs `stiffness_scale` times stiffer,
/// stretch limited to 10 % when `limited`, pinned by `pins`, alone in a world of step h.
inline World hanging_cloth(std::uint32_t n, const std::string& integrator, Real h, bool limited,
                           Real stiffness_scale = 1, GridPinPreset pins = GridPinPreset::kTopRow) {
  GridClothSpec spec;
  spec.nx = spec.ny = n;
  spec.width = spec.height = 2;
  spec.total_mass = 4;
  spec.center = Vec3(0, 1.5, 0);
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 30 * stiffness_scale, 0.05};
  params.spring(SpringKind::kShear) = {true, 8 * stiffness_scale, 0.02};
  params.spring(SpringKind::kBend) = {true, 1 * stiffness_scale, 0.005};
  params.drag = 0.01;
  params.stretch.enabled = limited;
  params.stretch.max_strain = 0.1;
  ClothBody body("sheet", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 make_integrator(integrator));
  for (std::uint32_t p : grid_pin_indices(spec, pins)) body.pin(p);
  World world(WorldSettings{Vec3(0, -9.81, 0), h, 100, 6});
  world.add_body(std::move(body));
  return world;
}

/// The pins' height less the lowest particle's.
inline Real sag_of(const ClothBody& body) {
  Real top = -1e300, lowest = 1e300;
  for (std::uint32_t p = 0; p < body.state().size(); ++p) {
    if (body.is_pinned(p)) top = std::max(top, body.state().x[p].y());
    lowest = std::min(lowest, body.state().x[p].y());
  }
  return top - lowest;
}

/// `count` balls of `radius` in a row along x from `first`, `spacing` apart: the haptic proxies
/// of several clients pressed into a cloth.
inline std::vector<Collider> balls_in_a_row(int count, const Vec3& first, Real spacing,
                                            Real radius) {
  std::vector<Collider> balls;
  for (int c = 0; c < count; ++c) {
    Collider ball;
    ball.shape = Collider::Shape::kSphere;
    ball.center = first + Vec3(spacing * c, 0, 0);
    ball.radius = radius;
    balls.push_back(ball);
  }
  return balls;
}

}  // namespace felt::test
