#pragma once
// Inverse dynamics: after the integrator, pull over-stretched springs back (thesis 1 §4.6), and
// optionally push over-compressed ones apart: with every spring force switched off that is the
// spring-less cloth of Fuhrmann et al. 2003, driven by constraint projection alone.

#include <span>

#include "core/cloth/cloth_model.hpp"
#include "core/integrate/particle_state.hpp"

namespace felt {

struct StretchLimit {
  bool enabled = false;
  Real max_strain = 0.1;  ///< s_max − 1: the thesis uses 10% in its example, 15% in its code
  /// 1 − s_min: a spring shorter than (1 − max_compression) r is pushed apart (Fuhrmann et al.
  /// 2003); negative switches it off
  Real max_compression = -1;
  int iterations = 4;  ///< Gauss–Seidel sweeps; stops early once no spring is out of bounds
  /// Provot position correction (structural and shear springs).
  bool position_correction = true;
  /// Vassilev et al. 2001 velocity correction: the velocities of both ends of a too-long
  /// spring get the same component along it, so the stretch stops growing.
  bool velocity_correction = false;
};

/// Applies the enabled corrections to `state` after a step of length h. Pinned particles
/// (inverse mass 0) never move: the other end is moved the whole way instead (Provot).
/// Returns the number of sweeps taken.
int limit_stretch(const ClothModel& model, std::span<const Real> inv_mass,
                  const StretchLimit& limit, Real h, ParticleState& state);

}  // namespace felt
