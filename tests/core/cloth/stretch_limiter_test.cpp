// Provot position correction and Vassilev velocity correction (thesis 1 §4.6).

#include "core/cloth/stretch_limiter.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/cloth/cloth_body.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

ClothModel one_spring(Real rest) {
  ClothModel model;
  model.rest_positions = {Vec3::Zero(), Vec3(rest, 0, 0)};
  model.uv = {Vec2::Zero(), Vec2::Zero()};
  model.mass = {1, 1};
  model.springs = {{0, 1, rest, SpringKind::kStructural}};
  return model;
}

StretchLimit limit(Real max_strain, int iterations = 1) {
  StretchLimit l;
  l.enabled = true;
  l.max_strain = max_strain;
  l.iterations = iterations;
  return l;
}

TEST(StretchLimiter, EqualMassesShortenAboutTheMidpoint) {
  const ClothModel model = one_spring(1);
  ParticleState state{{Vec3(0, 0, 0), Vec3(2, 0, 0)}, {Vec3::Zero(), Vec3::Zero()}};
  const std::vector<Real> inv_mass = {1, 1};
  limit_stretch(model, inv_mass, limit(0.1), 0.01, state);
  EXPECT_NEAR((state.x[0] - Vec3(0.45, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((state.x[1] - Vec3(1.55, 0, 0)).norm(), 0, 1e-15);
  // velocities follow the correction: Δx / h
  EXPECT_NEAR((state.v[0] - Vec3(45, 0, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR((state.v[1] - Vec3(-45, 0, 0)).norm(), 0, 1e-12);
}

TEST(StretchLimiter, AFixedEndStaysAndTheFreeEndMovesTheWholeWay) {
  const ClothModel model = one_spring(1);
  ParticleState state{{Vec3(0, 0, 0), Vec3(0, -3, 0)}, {Vec3::Zero(), Vec3::Zero()}};
  const std::vector<Real> inv_mass = {0, 1};
  limit_stretch(model, inv_mass, limit(0.15), 0.01, state);
  EXPECT_EQ(state.x[0], Vec3::Zero());
  EXPECT_NEAR((state.x[1] - Vec3(0, -1.15, 0)).norm(), 0, 1e-15);
}

TEST(StretchLimiter, IteratedSweepsBringEverySpringWithinTheLimit) {
  GridClothSpec spec;
  spec.nx = spec.ny = 10;
  const ClothModel model = make_grid_cloth(spec);
  std::vector<Real> inv_mass(model.particle_count(), 1);
  const auto pins = grid_pin_indices(spec, GridPinPreset::kTopCorners);
  for (std::uint32_t p : pins) inv_mass[p] = 0;
  // a random, badly stretched state with the pins in place
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> noise(-0.08, 0.08);
  ParticleState state{model.rest_positions,
                      std::vector<Vec3>(model.particle_count(), Vec3::Zero())};
  for (std::size_t p = 0; p < state.size(); ++p) {
    if (inv_mass[p] > 0) state.x[p] = 1.4 * state.x[p] + Vec3(noise(rng), noise(rng), noise(rng));
  }
  limit_stretch(model, inv_mass, limit(0.1, 1000), 1e-3, state);
  for (const Spring& s : model.springs) {
    if (s.kind == SpringKind::kBend) continue;
    EXPECT_LE((state.x[s.i] - state.x[s.j]).norm(), 1.1 * s.rest_length * (1 + 1e-6));
  }
  for (std::uint32_t p : pins) EXPECT_EQ(state.x[p], model.rest_positions[p]);
}

TEST(StretchLimiter, VelocityCorrectionStopsTheStretchAndKeepsMomentum) {
  const ClothModel model = one_spring(1);
  ParticleState state{{Vec3(0, 0, 0), Vec3(1.5, 0, 0)}, {Vec3(-1, 2, 0), Vec3(3, 0, 1)}};
  const std::vector<Real> inv_mass = {1, 0.5};  // masses 1 and 2
  StretchLimit l = limit(0.1);
  l.position_correction = false;
  l.velocity_correction = true;
  const Vec3 momentum = state.v[0] + 2 * state.v[1];
  limit_stretch(model, inv_mass, l, 0.01, state);
  EXPECT_NEAR(state.v[0].x(), state.v[1].x(), 1e-15);  // no more relative motion along x
  EXPECT_NEAR((state.v[0] + 2 * state.v[1] - momentum).norm(), 0, 1e-14);
  EXPECT_EQ(state.v[0].y(), 2);  // components across the spring are untouched
  EXPECT_EQ(state.v[1].z(), 1);
}

TEST(StretchLimiter, CompressionLimitPushesShortSpringsApart) {
  const ClothModel model = one_spring(1);
  ParticleState state{{Vec3(0, 0, 0), Vec3(0.5, 0, 0)}, {Vec3::Zero(), Vec3::Zero()}};
  const std::vector<Real> inv_mass = {1, 1};
  StretchLimit l = limit(0.1);
  l.max_compression = 0.1;
  limit_stretch(model, inv_mass, l, 0.01, state);
  EXPECT_NEAR((state.x[1] - state.x[0]).norm(), 0.9, 1e-15);
  EXPECT_NEAR(0.5 * (state.x[0] + state.x[1]).x(), 0.25, 1e-15);  // about the midpoint
}

TEST(StretchLimiter, SpringlessClothIsHeldByConstraintsAlone) {
  // Fuhrmann et al. 2003: no spring forces at all; every structural and shear edge stays within
  // [0.95, 1.05] of its rest length after each step, and the cloth still hangs and swings
  GridClothSpec spec;
  spec.nx = spec.ny = 10;
  spec.plane = GridClothSpec::Plane::kXZ;
  ClothParams params;
  for (SpringParams& sp : params.springs) sp.enabled = false;
  params.stretch = limit(0.05, 200);
  params.stretch.max_compression = 0.05;
  World world(WorldSettings{Vec3(0, -9.81, 0), 1e-3, 100, 6});
  world.add_body(ClothBody("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                           make_integrator("symplectic_euler")));
  for (std::uint32_t pin : grid_pin_indices(spec, GridPinPreset::kTopCorners)) {
    world.cloths()[0].pin(pin);
  }
  const ClothBody& body = world.cloths()[0];
  Real lowest = 0;
  for (int n = 0; n < 1000; ++n) {
    ASSERT_EQ(world.step().flags, kStepOk) << "step " << n;
    for (const Spring& s : body.model().springs) {
      if (s.kind == SpringKind::kBend) continue;
      const Real ratio = (body.state().x[s.i] - body.state().x[s.j]).norm() / s.rest_length;
      ASSERT_LE(ratio, 1.05 + 1e-3) << "step " << n;
      ASSERT_GE(ratio, 0.95 - 1e-3) << "step " << n;
    }
    lowest = std::min(lowest, body.state().x[99].y());
  }
  // undamped, it swings like a hinged plate: the far corner passes ~1 m below the pins
  EXPECT_LT(lowest, -0.9);
}

TEST(StretchLimiter, HangingClothNeverExceedsTheLimitAfterAnyStep) {
  GridClothSpec spec;
  spec.nx = spec.ny = 12;
  spec.total_mass = 2;  // heavy on soft springs: sags far beyond 10% without the limit
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 30, 0.05};
  params.spring(SpringKind::kShear) = {true, 10, 0.02};
  params.spring(SpringKind::kBend) = {true, 1, 0.005};
  params.drag = 0.02;
  auto run = [&](bool limited) {
    ClothParams p = params;
    p.stretch = limit(0.1, 50);
    p.stretch.enabled = limited;
    World world(WorldSettings{Vec3(0, -9.81, 0), 1e-3, 100, 6});
    world.add_body(ClothBody("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), p,
                             make_integrator("symplectic_euler")));
    for (std::uint32_t pin : grid_pin_indices(spec, GridPinPreset::kTopCorners)) {
      world.cloths()[0].pin(pin);
    }
    Real worst = 0;
    for (int n = 0; n < 3000; ++n) {
      world.step();
      worst = std::max(worst, world.cloths()[0].max_strain());
    }
    return worst;
  };
  EXPECT_GT(run(false), 0.3);
  EXPECT_LE(run(true), 0.1 + 1e-3);
}

}  // namespace
}  // namespace felt
