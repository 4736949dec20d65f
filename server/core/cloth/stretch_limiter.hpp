#pragma once
// Inverse dynamics: after the integrator, pull over-stretched springs back (thesis 1 §4.6), and
// optionally push over-compressed ones apart: with every spring force switched off that is the
// spring-less cloth of Fuhrmann et al. 2003, driven by constraint projection alone.
//
// Positions are projected onto the bounds; velocities are never given the displacement (Provot's
// Δx/h turns the correction of a stretch left over from earlier steps into a kick). Instead the
// velocities along springs at a bound are filtered so that they stop moving past it (Vassilev et
// al. 2001): each such filter is a perfectly inelastic, momentum-conserving impulse, so the
// limiter never adds kinetic energy, whatever the integrator, the step or the state.

#include <cstdint>
#include <span>
#include <vector>

#include "core/cloth/cloth_model.hpp"
#include "core/cloth/long_range_attachments.hpp"
#include "core/integrate/particle_state.hpp"

namespace felt {

struct StretchLimit {
  bool enabled = false;
  Real max_strain = 0.1;  ///< s_max − 1: the thesis uses 10% in its example, 15% in its code
  /// 1 − s_min: a spring shorter than (1 − max_compression) r is pushed apart (Fuhrmann et al.
  /// 2003); negative switches it off
  Real max_compression = -1;
  /// The most Gauss–Seidel sweeps of each pass. A pass stops earlier, once no spring is more
  /// than kStretchTolerance of its bound's strain beyond it.
  int iterations = 30;
  /// Positions projected onto the bounds (Provot 1995; Fuhrmann et al. 2003 for compression).
  bool position_correction = true;
  /// Velocities along springs at a bound filtered so they do not move past it (Vassilev,
  /// Spanlang & Chrysanthou 2001).
  bool velocity_correction = true;
};

/// How far past its bound a spring may be left, relative to the bound's strain: a 10 % limit
/// holds to 10.1 %.
inline constexpr Real kStretchTolerance = 0.01;

/// What one pass did.
struct StretchLimitStats {
  int position_sweeps = 0;
  int velocity_sweeps = 0;
};

/// The limiter of one cloth: keeps the cloth's long range attachments, worked out again when
/// its pinned particles change.
class StretchLimiter {
 public:
  /// Applies the enabled corrections to `state` after a (sub)step of length h. Pinned particles
  /// (inverse mass 0) never move: the other end moves the whole way instead (Provot).
  StretchLimitStats apply(const ClothModel& model, std::span<const Real> inv_mass,
                          const StretchLimit& limit, Real h, ParticleState& state);

 private:
  void update_attachments(const ClothModel& model, std::span<const Real> inv_mass);

  std::vector<std::uint32_t> pinned_;  ///< the pinned particles the attachments were made for
  std::vector<std::uint32_t> scratch_pinned_;  ///< the pinned particles now, compared with pinned_
  std::vector<Attachment> attachments_;
  bool attachments_valid_ = false;
};

}  // namespace felt
