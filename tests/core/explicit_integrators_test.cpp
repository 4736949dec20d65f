// Explicit Euler and symplectic Euler against the analytic harmonic oscillator and free fall.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/explicit_integrators.hpp"

namespace felt {
namespace {

/// One particle on a spring to the origin (f = −k x) under a constant force `push`.
class Oscillator final : public DynamicSystem {
 public:
  Oscillator(Real mass, Real stiffness, Vec3 push = Vec3::Zero())
      : inv_mass_{1 / mass}, stiffness_(stiffness), push_(push) {}
  std::span<const Real> inv_mass() const override { return inv_mass_; }
  void compute_forces(std::span<const Vec3> x, std::span<const Vec3>, Real,
                      std::span<Vec3> f) const override {
    f[0] = -stiffness_ * x[0] + push_;
  }
  Real energy(const ParticleState& s) const {
    return 0.5 / inv_mass_[0] * s.v[0].squaredNorm() + 0.5 * stiffness_ * s.x[0].squaredNorm();
  }

 private:
  std::vector<Real> inv_mass_;
  Real stiffness_;
  Vec3 push_;
};

ParticleState start_at(const Vec3& x, const Vec3& v = Vec3::Zero()) {
  return {{x}, {v}};
}

// ω = 2π rad/s: one period per second
constexpr Real kMass = 1;
const Real kStiffness = 4 * M_PI * M_PI;
const Real kOmega = 2 * M_PI;

/// Largest error of the state (x, v/ω) against x0 cos ωt over one period, with step h.
/// (The error at exactly one period is no measure: symplectic Euler is superconvergent there.)
Real oscillator_error(Integrator& integrator, Real h) {
  Oscillator system(kMass, kStiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const int steps = static_cast<int>(std::lround(1.0 / h));
  Real worst = 0;
  for (int n = 0; n < steps; ++n) {
    integrator.step(system, state, n * h, h);
    const Real t = (n + 1) * h;
    worst = std::max(worst, std::hypot(state.x[0].x() - std::cos(kOmega * t),
                                       state.v[0].x() / kOmega + std::sin(kOmega * t)));
  }
  return worst;
}

Real measured_order(Integrator& integrator) {
  const Real h = 1e-3;
  const Real e1 = oscillator_error(integrator, h);
  const Real e2 = oscillator_error(integrator, h / 2);
  const Real e4 = oscillator_error(integrator, h / 4);
  // two estimates of the order, averaged: log2(e(h)/e(h/2)), log2(e(h/2)/e(h/4))
  return 0.5 * (std::log2(e1 / e2) + std::log2(e2 / e4));
}

TEST(ExplicitIntegrators, ConvergeWithOrderOne) {
  ExplicitEuler euler;
  SymplecticEuler symplectic;
  EXPECT_NEAR(measured_order(euler), 1.0, 0.05);
  EXPECT_NEAR(measured_order(symplectic), 1.0, 0.05);
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
}  // namespace felt
