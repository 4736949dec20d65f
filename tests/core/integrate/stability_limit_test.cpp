// The integrators' stability limits (core/integrate/stability_limit.hpp) against the closed forms
// of the literature, and against the integrators themselves stepping a damped oscillator just
// inside and just outside the limit each one states.

#include <cmath>
#include <limits>
#include <memory>
#include <string_view>

#include <gtest/gtest.h>

#include "core/integrate/integrator.hpp"
#include "core/integrate/oscillator.hpp"
#include "core/integrate/runge_kutta_integrators.hpp"

namespace felt::test {
namespace {

constexpr std::array<Real, 2> kEuler{1, 1};
constexpr std::array<Real, 3> kMidpoint{1, 1, 0.5};
constexpr std::array<Real, 5> kRk4{1, 1, 1.0 / 2, 1.0 / 6, 1.0 / 24};

TEST(StabilityLimit, ClosedFormsOfTheLiterature) {
  // Störmer–Verlet: ωh < 2 (Hairer, Lubich & Wanner, GNI §I.5); with damping ω²h² + 2ch ≤ 4,
  // and ω²h² + 4ch ≤ 4 for the cloth's Verlet family
  EXPECT_DOUBLE_EQ(verlet_step_limit({100, 0}), 0.2);
  EXPECT_DOUBLE_EQ(second_order_verlet_step_limit({100, 0}), 0.2);
  const Real h = verlet_step_limit({100, 3}), h2 = second_order_verlet_step_limit({100, 3});
  EXPECT_NEAR(100 * h * h + 2 * 3 * h, 4, 1e-12);
  EXPECT_NEAR(100 * h2 * h2 + 4 * 3 * h2, 4, 1e-12);
  // RK4 on the imaginary axis up to 2√2, on the negative real axis up to 2.7852935634
  // (Hairer & Wanner, Solving ODEs II, §IV.2)
  EXPECT_NEAR(polynomial_step_limit(kRk4, {1, 0}), 2 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(polynomial_step_limit(kRk4, {0, 1}), 2.7852935634, 1e-9);
  // forward Euler: |1 + hλ| ≤ 1 gives h ≤ c/ω² for a complex pair, 2/|λ| for real roots
  EXPECT_NEAR(polynomial_step_limit(kEuler, {100, 2}), 2.0 / 100, 1e-12);
  const Real fastest = (10 + std::sqrt(96.0)) / 2;  // λ² + 10λ + 1 = 0
  EXPECT_NEAR(polynomial_step_limit(kEuler, {1, 10}), 2 / fastest, 1e-12);
  // nothing to grow: no limit
  EXPECT_EQ(polynomial_step_limit(kEuler, {0, 0}), kNoStepLimit);
}

TEST(StabilityLimit, ExplicitEulerAndMidpointHaveNoStepOnAnUndampedMode) {
  // |1 + iωh|² = 1 + (ωh)² and |R(iωh)|² = 1 + (ωh)⁴/4 exceed 1 at every h
  EXPECT_EQ(polynomial_step_limit(kEuler, {1e4, 0}), 0);
  EXPECT_EQ(polynomial_step_limit(kMidpoint, {1e4, 0}), 0);
  EXPECT_EQ(polynomial_step_limit(kMidpoint, {1, 0}), 0);
  // a little damping gives each a step
  EXPECT_GT(polynomial_step_limit(kMidpoint, {1e4, 1}), 0);
}

/// The amplitude |(x, v/ω)| after 20000 steps of h from x = 1, relative to the start; infinity
/// once it is not finite.
Real amplitude_after(Integrator& integrator, Real omega, Real rate, Real h) {
  Oscillator system(1, omega * omega, Vec3::Zero(), rate);
  ParticleState state = start_at(Vec3(1, 0, 0));
  integrator.reset();
  for (int n = 0; n < 20000; ++n) integrator.step(system, state, n * h, h);
  const Real amplitude = std::hypot(state.x[0].x(), state.v[0].x() / omega);
  return std::isfinite(amplitude) ? amplitude : std::numeric_limits<Real>::infinity();
}

TEST(StabilityLimit, EachIntegratorDecaysJustInsideItsLimitAndGrowsJustOutside) {
  // ω = 100/s, from a light damping (ζ = 0.02) to an overdamped one (ζ = 1.5)
  for (Real rate : {4.0, 40.0, 120.0, 300.0}) {
    for (std::string_view name : {"explicit_euler", "symplectic_euler", "midpoint", "rk4", "verlet",
                                  "velocity_verlet", "leapfrog"}) {
      SCOPED_TRACE(std::string(name) + " at c = " + std::to_string(rate));
      const auto integrator = make_integrator(name);
      const Real limit = integrator->step_limit({1e4, rate});
      ASSERT_GT(limit, 0);
      ASSERT_LT(limit, 1);
      EXPECT_LT(amplitude_after(*integrator, 100, rate, 0.97 * limit), 1);
      EXPECT_GT(amplitude_after(*integrator, 100, rate, 1.03 * limit), 1);
    }
  }
}

TEST(StabilityLimit, AdaptiveRkForcedToOneInternalStepDecaysJustInsideItsLimitAndGrowsOutside) {
  // one internal step a call, accepted whatever its error: Dormand–Prince 5 at a fixed step
  AdaptiveRungeKutta forced(AdaptiveRungeKutta::kDefaultTolerance, 1);
  for (Real rate : {0.0, 4.0, 40.0, 120.0, 300.0}) {
    SCOPED_TRACE("c = " + std::to_string(rate));
    const Real limit = forced.internal_step_limit({1e4, rate});
    ASSERT_GT(limit, 0);
    ASSERT_LT(limit, 1);
    EXPECT_LT(amplitude_after(forced, 100, rate, 0.97 * limit), 1);
    EXPECT_GT(amplitude_after(forced, 100, rate, 1.03 * limit), 1);
  }
  // undamped, the part of the imaginary axis its stability region holds: |R(iy)| first
  // exceeds 1 at y = 0.9972 (a scan of the polynomial; Hairer & Wanner, Solving ODEs II, §IV.2,
  // Fig. 2.1 shows the region leaving the axis near ±i)
  EXPECT_NEAR(forced.internal_step_limit({1, 0}), 0.9972, 1e-4);
}

TEST(StabilityLimit, ImplicitAndAdaptiveIntegratorsHaveNone) {
  for (std::string_view name : {"adaptive_rk", "implicit_euler", "imex", "desbrun", "kang", "xpbd",
                                "projective_dynamics"}) {
    EXPECT_EQ(make_integrator(name)->step_limit({1e8, 0}), kNoStepLimit) << name;
  }
}

}  // namespace
}  // namespace felt::test
