#pragma once
// A body's motion relative to its centre of mass, and taking energy out of it without touching
// its momentum: how a rescued step gives back the energy numerical growth added before the
// health check saw it (ClothSystem, SolidSystem). Scaling the velocities back onto the energy the
// balance allows is a projection onto the invariant, as Hairer, Lubich and Wanner's projection
// methods do (Geometric Numerical Integration, §IV.4).

#include <algorithm>
#include <cmath>
#include <span>

#include "core/math/types.hpp"

namespace felt {

/// The free particles' (inverse mass above 0) centre-of-mass velocity and the kinetic energy
/// of their motion relative to it; for a body held in place (pinned particles, anchors), whose
/// momentum is not its own to keep, zero and all of their kinetic energy.
struct InternalMotion {
  Vec3 centre_velocity = Vec3::Zero();
  Real energy = 0;  ///< J
};

/// The internal motion of particles with velocities `v`, inverse masses `inv_mass` and masses
/// mass_of(p), of a body `anchored` by springs or not (pinned particles hold it either way).
template <class MassOf>
InternalMotion internal_motion(std::span<const Vec3> v, std::span<const Real> inv_mass,
                               MassOf mass_of, bool anchored) {
  Real mass = 0;
  Vec3 momentum = Vec3::Zero();
  bool held = anchored;
  for (std::size_t p = 0; p < v.size(); ++p) {
    if (inv_mass[p] == 0) {
      held = true;
      continue;
    }
    mass += mass_of(p);
    momentum += mass_of(p) * v[p];
  }
  InternalMotion motion;
  if (mass == 0) return motion;
  if (!held) motion.centre_velocity = momentum / mass;
  for (std::size_t p = 0; p < v.size(); ++p) {
    if (inv_mass[p] == 0) continue;
    motion.energy += 0.5 * mass_of(p) * (v[p] - motion.centre_velocity).squaredNorm();
  }
  return motion;
}

/// The factor that scales internal motion of kinetic energy `energy` down by `excess` J (to
/// rest when it holds no more).
inline Real internal_motion_factor(Real energy, Real excess) {
  if (!(energy > 0)) return 1;
  return std::sqrt(std::max(Real{0}, 1 - excess / energy));
}

/// Scales the free particles' velocities relative to `centre_velocity` by `factor`: their
/// momentum stays, their internal kinetic energy changes by factor².
inline void scale_internal_motion(std::span<Vec3> v, std::span<const Real> inv_mass,
                                  const Vec3& centre_velocity, Real factor) {
  for (std::size_t p = 0; p < v.size(); ++p) {
    if (inv_mass[p] != 0) v[p] = centre_velocity + factor * (v[p] - centre_velocity);
  }
}

}  // namespace felt
