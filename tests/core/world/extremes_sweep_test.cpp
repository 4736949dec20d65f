// A small sweep of the extremes (issue 27): every cloth integrator at soft and stiff springs, light
// and heavy cloths, short and long steps on a 4 × 4 cloth, and each solid model under each of its
// integrators likewise. None may crash, hang or leave a non-finite value, and each either stays
// within an energy bound or is reported as rescued or unrecoverable. scripts/bench-extremes runs
// a larger one.

#include <gtest/gtest.h>

#include <cstdio>
#include <string_view>
#include <utility>
#include <vector>

#include "core/cloth/cloth_grid.hpp"
#include "core/solids/solid_fixtures.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

constexpr Real kGravity = 9.81;
constexpr int kSteps = 40;

/// Kinetic, elastic and gravitational energy of a cloth in steps of h, as the health check
/// counts them (xpbd's springs at the stiffness its projection applies).
Real mechanical_energy(const ClothBody& body, Real h) {
  return body.kinetic_energy() + body.elastic_energy_in_steps_of(h) + body.gravitational_energy();
}

bool finite(const ClothBody& body, Real h) {
  for (std::size_t p = 0; p < body.state().size(); ++p) {
    if (!body.state().x[p].allFinite() || !body.state().v[p].allFinite()) return false;
  }
  return std::isfinite(mechanical_energy(body, h));
}

TEST(ExtremesSweep, ClothsStayFiniteAndWithinAnEnergyBoundOrAreReported) {
  int runs = 0, reported = 0;
  for (std::string_view integrator : integrator_names()) {
    for (const Real stiffness : {1.0, 1e3, 1e6}) {
      for (const Real mass : {1e-3, 1.0, 1e3}) {
        for (const Real h : {1e-4, 1e-2}) {
          GridClothSpec spec;
          spec.nx = spec.ny = 4;
          spec.total_mass = mass;
          ClothParams params;
          params.spring(SpringKind::kStructural) = {true, stiffness, 1e-3 * stiffness * h};
          params.spring(SpringKind::kShear) = {true, stiffness / 4, 0};
          params.spring(SpringKind::kBend) = {true, stiffness / 40, 0};
          World world(WorldSettings{.gravity = Vec3(0, -kGravity, 0), .time_step = h});
          ClothBody body("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                         make_integrator(integrator));
          for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) body.pin(p);
          world.add_body(std::move(body));
          const ClothBody& cloth = std::as_const(world).cloths()[0];
          const Real start = mechanical_energy(cloth, h);
          // what gravity can give the cloth falling through its own size (1 m), and as much
          // again for the swing of a symplectic scheme's energy
          const Real bound = 2 * mass * kGravity * 1;
          StepFlags flags;
          for (int n = 0; n < kSteps; ++n) {
            flags |= world.step().flags;
            ASSERT_TRUE(finite(cloth, h))
                << integrator << " k " << stiffness << " m " << mass << " h " << h << " step " << n;
          }
          ++runs;
          if (!flags.ok()) {
            ++reported;
            continue;
          }
          EXPECT_LE(mechanical_energy(cloth, h) - start, bound)
              << integrator << " k " << stiffness << " m " << mass << " h " << h;
        }
      }
    }
  }
  std::printf("%d cloth runs, %d reported rescued or unrecoverable\n", runs, reported);
}

TEST(ExtremesSweep, SolidsStayFiniteAndWithinAnEnergyBoundOrAreReported) {
  int runs = 0, reported = 0;
  const std::vector<std::string_view> force_model_integrators = {
      kTimeCorrectedVerlet, "explicit_euler", "symplectic_euler", "midpoint", "rk4"};
  const std::vector<std::string_view> own_update = {kTimeCorrectedVerlet};
  for (const SolidModel model :
       {SolidModel::kMassSpring, SolidModel::kCorotatedFem, SolidModel::kShapeMatching}) {
    // shape matching moves its nodes by its own update
    for (const std::string_view integrator :
         model == SolidModel::kShapeMatching ? own_update : force_model_integrators) {
      for (const Real stiffness : {1.0, 1e4}) {
        for (const Real node_mass : {1e-3, 10.0}) {
          for (const Real h : {1e-3, 0.05}) {
            SolidMaterial material = model == SolidModel::kCorotatedFem
                                         ? test::fem(node_mass, 100 * stiffness, 0.3, 0.01)
                                         : test::mass_spring(node_mass, stiffness, stiffness, 1);
            material.model = model;
            World world(WorldSettings{.gravity = Vec3(0, -kGravity, 0), .time_step = h});
            SolidBody solid("cube", test::box({2, 2, 2}, 0.25), material);
            if (integrator != kTimeCorrectedVerlet)
              solid.set_integrator(make_integrator(integrator));
            // a solid too stiff for its node mass at this step is refused by the scene loader
            if (h / solid.stable_time_step() > 2000) continue;
            world.add_body(std::move(solid));
            world.add_collider(Collider{});  // the floor y = 0 it lands on
            const SolidBody& body = std::as_const(world).solids().bodies()[0];
            const Vec3 g(0, -kGravity, 0);
            const Real start =
                body.kinetic_energy() + body.elastic_energy() + body.gravitational_energy(g);
            StepFlags flags;
            for (int n = 0; n < kSteps; ++n) {
              flags |= world.step().flags;
              ASSERT_TRUE(test::all_finite(body))
                  << static_cast<int>(model) << " " << integrator << " k " << stiffness << " m "
                  << node_mass << " h " << h << " step " << n;
            }
            ++runs;
            if (!flags.ok()) {
              ++reported;
              continue;
            }
            const Real energy =
                body.kinetic_energy() + body.elastic_energy() + body.gravitational_energy(g);
            EXPECT_LE(energy - start, 27 * node_mass * kGravity * 0.5)
                << static_cast<int>(model) << " " << integrator << " k " << stiffness << " m "
                << node_mass << " h " << h;
          }
        }
      }
    }
  }
  std::printf("%d solid runs, %d reported rescued or unrecoverable\n", runs, reported);
}

}  // namespace
}  // namespace felt
