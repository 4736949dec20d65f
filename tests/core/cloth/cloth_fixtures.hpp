#pragma once
// Small bodies and checks shared by the core tests.

#include <cstdint>
#include <memory>
#include <random>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "core/cloth/cloth_body.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/world/world.hpp"

namespace felt::test {

/// Two particles joined by one structural spring of rest length `rest` along x, the first
/// pinned at the origin: a 1-D oscillator m ẍ = −k (x − r) along the spring (linear, f = −k x,
/// when rest is 0).
inline ClothBody spring_pair(Real mass, Real stiffness, Real rest, Real damping,
                             std::string_view integrator) {
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {Vec3::Zero(), Vec3(rest, 0, 0)};
  model->uv = {Vec2::Zero(), Vec2::Zero()};
  model->mass = {mass, mass};
  model->springs = {{0, 1, rest, SpringKind::kStructural}};
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, stiffness, damping};
  ClothBody body("pair", model, params, make_integrator(integrator));
  body.pin(0);
  return body;
}

/// A small nx × ny grid cloth with structural springs (k, c) and fixed, softer shear (70, 0.1)
/// and bend (9, 0.02) springs and drag 0.05: a body with every kind of force term, for checks
/// of forces, Jacobians and single steps.
inline ClothBody small_grid_body(std::uint32_t nx, std::uint32_t ny, Real structural_stiffness,
                                 Real structural_damping, std::string_view integrator) {
  GridClothSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, structural_stiffness, structural_damping};
  params.spring(SpringKind::kShear) = {true, 70, 0.1};
  params.spring(SpringKind::kBend) = {true, 9, 0.02};
  params.drag = 0.05;
  return ClothBody("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                   make_integrator(integrator));
}

/// A 6 × 6 cloth (structural 500 N/m, shear 100 N/m) hanging from its pinned top row, stepped
/// 400 times at 5 ms: the pins must stay exactly put while the rest sags. `every_step_ok`
/// also requires that no step needed a rescue. Returns the world for further checks.
inline World expect_top_row_pins_hold(std::string_view integrator, bool every_step_ok) {
  GridClothSpec spec;
  spec.nx = spec.ny = 6;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 500, 0.1};
  params.spring(SpringKind::kShear) = {true, 100, 0.05};
  World world(WorldSettings{Vec3(0, -9.81, 0), 5e-3, 100, 6});
  world.add_body(ClothBody("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                           make_integrator(integrator)));
  const auto pins = grid_pin_indices(spec, GridPinPreset::kTopRow);
  for (std::uint32_t p : pins) world.cloths()[0].pin(p);
  const std::vector<Vec3> start = world.cloths()[0].state().x;
  for (int n = 0; n < 400; ++n) {
    const StepReport report = world.step();
    if (every_step_ok) {
      EXPECT_EQ(report.flags, StepFlags{}) << "step " << n;
    }
  }
  const ClothBody& body = world.cloths()[0];
  for (std::uint32_t p : pins) EXPECT_EQ(body.state().x[p], start[p]);
  EXPECT_LT(body.state().x[30].y(), start[30].y() - 0.002);  // the rest sags
  return world;
}

/// Kinetic, elastic and gravitational energy, the last measured from the positions `start`, J.
inline Real total_energy(const ClothBody& body, const std::vector<Vec3>& start) {
  Real energy = body.kinetic_energy() + body.elastic_energy();
  for (std::size_t i = 0; i < start.size(); ++i) {
    energy -= body.model().mass[i] * body.gravity().dot(body.state().x[i] - start[i]);
  }
  return energy;
}

inline bool all_finite(const ParticleState& state) {
  for (std::size_t p = 0; p < state.size(); ++p) {
    if (!state.x[p].allFinite() || !state.v[p].allFinite()) return false;
  }
  return true;
}

inline void expect_vec_near(const Vec3& got, const Vec3& want, Real tolerance) {
  EXPECT_NEAR(got.x(), want.x(), tolerance);
  EXPECT_NEAR(got.y(), want.y(), tolerance);
  EXPECT_NEAR(got.z(), want.z(), tolerance);
}

/// A 30 × 30 grid pinned at its two top corners, every free particle moved 1.4 times as far from
/// the grid's centre and shaken by up to 3 cm (a fixed seed): far beyond any stretch limit, and
/// slow for Gauss–Seidel (hundreds of sweeps, each taking about 1 % off the excess).
struct StretchedGrid {
  ClothModel model;
  std::vector<Real> inv_mass;
  std::vector<std::uint32_t> pins;
  ParticleState state;
};

inline StretchedGrid badly_stretched_grid() {
  GridClothSpec spec;
  spec.nx = spec.ny = 30;
  StretchedGrid g{
      make_grid_cloth(spec), {}, grid_pin_indices(spec, GridPinPreset::kTopCorners), {}};
  g.inv_mass.assign(g.model.particle_count(), 1);
  for (std::uint32_t p : g.pins) g.inv_mass[p] = 0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> noise(-0.03, 0.03);
  g.state = {g.model.rest_positions, std::vector<Vec3>(g.model.particle_count(), Vec3::Zero())};
  for (std::size_t p = 0; p < g.state.size(); ++p) {
    if (g.inv_mass[p] > 0)
      g.state.x[p] = 1.4 * g.state.x[p] + Vec3(noise(rng), noise(rng), noise(rng));
  }
  return g;
}

}  // namespace felt::test
