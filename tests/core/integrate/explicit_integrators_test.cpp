// Explicit Euler and symplectic Euler against the analytic harmonic oscillator and free fall.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/integrate/explicit_integrators.hpp"
#include "core/integrate/oscillator.hpp"

namespace felt::test {
namespace {

TEST(ExplicitIntegrators, ConvergeWithOrderOne) {
  ExplicitEuler euler;
  SymplecticEuler symplectic;
  EXPECT_NEAR(measured_order(euler, 1e-3), 1.0, 0.05);
  EXPECT_NEAR(measured_order(symplectic, 1e-3), 1.0, 0.05);
}

TEST(ExplicitEuler, EnergyGrowsByTheAmplificationFactor) {
  // forward Euler multiplies the oscillator's energy by exactly 1 + (ωh)² each step
  ExplicitEuler euler;
  Oscillator system(kMass, kStiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const Real h = 1e-3;
  const Real e0 = system.energy(state);
  const int steps = 10000;
  for (int n = 0; n < steps; ++n) euler.step(system, state, n * h, h);
  const Real expected = e0 * std::pow(1 + kOmega * kOmega * h * h, steps);
  EXPECT_NEAR(system.energy(state) / expected, 1.0, 1e-9);
  EXPECT_GT(system.energy(state), 1.4 * e0);
}

TEST(SymplecticEuler, EnergyStaysBoundedOverLongRuns) {
  SymplecticEuler symplectic;
  Oscillator system(kMass, kStiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const Real h = 0.01;  // ωh ≈ 0.063
  const Real e0 = system.energy(state);
  Real max_error = 0;
  for (int n = 0; n < 100000; ++n) {
    symplectic.step(system, state, n * h, h);
    max_error = std::max(max_error, std::abs(system.energy(state) - e0) / e0);
  }
  // the modified energy is conserved; the true energy oscillates within O(ωh)
  EXPECT_LT(max_error, kOmega * h);
}

TEST(SymplecticEuler, StabilityLimitIsTwoOverOmega) {
  auto amplitude_after = [](Real h) {
    SymplecticEuler symplectic;
    Oscillator system(kMass, kStiffness);
    ParticleState state = start_at(Vec3(1, 0, 0));
    for (int n = 0; n < 200; ++n) symplectic.step(system, state, n * h, h);
    return std::sqrt(2 * system.energy(state) / kStiffness);
  };
  // below the limit the amplitude stays O(1); above it grows by |λ| ≈ 1.49 per step at 1.02×
  const Real limit = 2 / kOmega;
  EXPECT_LT(amplitude_after(0.98 * limit), 20.0);
  EXPECT_GT(amplitude_after(1.02 * limit), 1e6);
}

TEST(ExplicitIntegrators, FreeFallFollowsTheirDiscreteSolutions) {
  // with a constant force the schemes sum exactly: after n steps (t = nh)
  //   explicit Euler   x = ½ g t² − ½ g h t
  //   symplectic Euler x = ½ g t² + ½ g h t
  // so both are first order and err by ½ g h t in opposite directions
  const Vec3 g(0, -9.81, 0);
  const Real h = 1e-3;
  const int steps = 1000;
  const Real t = steps * h;
  Oscillator falling(kMass, 0, kMass * g);
  ExplicitEuler euler;
  SymplecticEuler symplectic;
  ParticleState a = start_at(Vec3::Zero());
  ParticleState b = start_at(Vec3::Zero());
  for (int n = 0; n < steps; ++n) {
    euler.step(falling, a, n * h, h);
    symplectic.step(falling, b, n * h, h);
  }
  const Vec3 exact = 0.5 * g * t * t;
  EXPECT_NEAR((a.x[0] - (exact - 0.5 * g * h * t)).norm(), 0, 1e-12);
  EXPECT_NEAR((b.x[0] - (exact + 0.5 * g * h * t)).norm(), 0, 1e-12);
  EXPECT_NEAR((a.v[0] - g * t).norm(), 0, 1e-12);
  EXPECT_NEAR((b.v[0] - g * t).norm(), 0, 1e-12);
}

TEST(IntegratorRegistry, MakesEveryListedNameAndNothingElse) {
  for (std::string_view name : integrator_names()) {
    auto integrator = make_integrator(name);
    ASSERT_NE(integrator, nullptr) << name;
    EXPECT_EQ(integrator->name(), name);
  }
  EXPECT_EQ(make_integrator("no_such_scheme"), nullptr);
}

}  // namespace
}  // namespace felt::test
