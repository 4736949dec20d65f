// The energy balance against budgets of known shape: slow steady growth is flagged by its
// windows; a bounded swing of the size a symplectic scheme shows is never flagged, nor is the
// work of applied forces; an infinite tolerance flags nothing.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/step/energy_balance.hpp"

namespace felt {
namespace {

constexpr Real kTolerance = 0.25;  // HealthSettings::energy_tolerance's default
constexpr int kWindow = 25;        // 0.25 s of 10 ms steps

/// The step at which a budget growing `factor` times a step from 1 (scale 1 + the budget's
/// rise, as a body's kinetic and elastic energy rises with it) is first flagged, or -1.
int first_flagged_step(Real factor, Real tolerance, int steps) {
  EnergyBalance balance;
  balance.reset(1);
  Real energy = 1;
  for (int s = 1; s <= steps; ++s) {
    energy *= factor;
    const Real scale = energy;
    if (!balance.within(balance.budget_after(energy, 0), scale, tolerance, kWindow)) return s;
    balance.accept(energy, 0, scale, kWindow);
  }
  return -1;
}

TEST(EnergyBalance, SlowGrowthIsFlaggedByItsWindows) {
  // 1 % a step: 28 % a window, which no single step shows
  const int flagged = first_flagged_step(1.01, kTolerance, 10 * kWindow);
  ASSERT_GT(flagged, kWindow);
  EXPECT_LE(flagged, 3 * kWindow);
}

TEST(EnergyBalance, ASwingOfASymplecticSchemeIsNeverFlagged) {
  // energy swinging by 1.5 times its size (ωh = 1.6, the edge of the stable steps' margin)
  // over a period of 7 steps, for 20 windows, without growing
  EnergyBalance balance;
  balance.reset(1);
  for (int s = 1; s <= 20 * kWindow; ++s) {
    const Real energy = 1 + 1.5 * std::pow(std::sin(std::numbers::pi * s / 7.0), 2);
    ASSERT_TRUE(balance.within(balance.budget_after(energy, 0), 1, kTolerance, kWindow))
        << "step " << s;
    balance.accept(energy, 0, 1, kWindow);
  }
}

TEST(EnergyBalance, WorkOfAppliedForcesIsNotGrowth) {
  // a push giving 0.5 J a step is what the energy rises by
  EnergyBalance balance;
  balance.reset(1);
  Real energy = 1;
  for (int s = 1; s <= 4 * kWindow; ++s) {
    energy += 0.5;
    ASSERT_TRUE(balance.within(balance.budget_after(energy, 0.5), energy, kTolerance, kWindow));
    balance.accept(energy, 0.5, energy, kWindow);
  }
}

TEST(EnergyBalance, AnInfiniteToleranceFlagsNothing) {
  EXPECT_EQ(first_flagged_step(1.8, std::numeric_limits<Real>::infinity(), 4 * kWindow), -1);
}

}  // namespace
}  // namespace felt
