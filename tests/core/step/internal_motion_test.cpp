// Taking energy out of a body's motion: a free body keeps its momentum and loses exactly what was
// asked, down to moving as one at most; a pinned body loses it about rest.

#include <array>
#include <vector>

#include <gtest/gtest.h>

#include "core/step/internal_motion.hpp"

namespace felt {
namespace {

constexpr std::array kMass{1.0, 2.0, 3.0};

Vec3 momentum(const std::vector<Vec3>& v) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t p = 0; p < v.size(); ++p) sum += kMass[p] * v[p];
  return sum;
}

Real kinetic_energy(const std::vector<Vec3>& v) {
  Real sum = 0;
  for (std::size_t p = 0; p < v.size(); ++p) sum += 0.5 * kMass[p] * v[p].squaredNorm();
  return sum;
}

const auto mass_of = [](std::size_t p) { return kMass[p]; };

TEST(InternalMotion, AFreeBodyKeepsItsMomentumAndLosesWhatWasAsked) {
  std::vector<Vec3> v{{1, 0, 0}, {0, 2, 0}, {-1, 0, 3}};
  const std::vector<Real> inv_mass{1.0, 0.5, 1.0 / 3};
  const Vec3 before_momentum = momentum(v);
  const Real before = kinetic_energy(v);
  const InternalMotion motion = internal_motion(v, inv_mass, mass_of, false);
  // the energy of the motion as one, ½ M |v_c|², is what scaling about the centre cannot take
  EXPECT_NEAR(before - motion.energy, 0.5 * 6 * motion.centre_velocity.squaredNorm(), 1e-12);
  const Real excess = 0.4 * motion.energy;
  scale_internal_motion(v, inv_mass, motion.centre_velocity,
                        internal_motion_factor(motion.energy, excess));
  EXPECT_NEAR(kinetic_energy(v), before - excess, 1e-12);
  EXPECT_LT((momentum(v) - before_momentum).norm(), 1e-12);
  // more than the internal motion holds: the body moves as one
  scale_internal_motion(v, inv_mass, motion.centre_velocity,
                        internal_motion_factor(motion.energy, 10 * motion.energy));
  for (const Vec3& velocity : v) EXPECT_LT((velocity - motion.centre_velocity).norm(), 1e-12);
}

TEST(InternalMotion, APinnedOrAnchoredBodyLosesItAboutRest) {
  const std::vector<Vec3> start{{1, 0, 0}, {0, 2, 0}, {0, 0, 0}};
  for (const bool pinned : {true, false}) {
    std::vector<Vec3> v = start;
    const std::vector<Real> inv_mass{1.0, 0.5, pinned ? 0.0 : 1.0 / 3};
    const InternalMotion motion = internal_motion(v, inv_mass, mass_of, !pinned);
    EXPECT_EQ(motion.centre_velocity, Vec3::Zero());
    EXPECT_NEAR(motion.energy, kinetic_energy(start), 1e-12);
    scale_internal_motion(v, inv_mass, motion.centre_velocity,
                          internal_motion_factor(motion.energy, motion.energy / 4));
    EXPECT_NEAR(kinetic_energy(v), 0.75 * kinetic_energy(start), 1e-12);
    EXPECT_EQ(v[2], Vec3::Zero());
  }
}

}  // namespace
}  // namespace felt
