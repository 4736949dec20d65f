#pragma once
// Inverse dynamics: after the integrator, pull over-stretched springs back (thesis 1 §4.6), and
// optionally push over-compressed ones apart: with every spring force switched off that is the
// spring-less cloth of Fuhrmann et al. 2003, driven by constraint projection alone.
//
// Gauss–Seidel sweeps over the springs do it where they converge in a few sweeps (a cloth hung
// from a row of pins); where they do not (most of a heavy cloth's weight carried by the few
// springs at two corners), the springs beyond their bounds are projected together by fast
// projection (Goldenthal et al. 2007), a few Newton steps of one sparse system each.
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
#include "core/cloth/spring_constraint_solve.hpp"
#include "core/integrate/particle_state.hpp"

namespace felt {

struct StretchLimit {
  bool enabled = false;
  Real max_strain = 0.1;  ///< s_max − 1: the thesis uses 10% in its example, 15% in its code
  /// 1 − s_min: a spring shorter than (1 − max_compression) r is pushed apart (Fuhrmann et al.
  /// 2003); negative switches it off
  Real max_compression = -1;
  /// The most Gauss–Seidel sweeps of each part of a pass. A part stops earlier, once no spring
  /// is more than kStretchTolerance of its bound's strain beyond it.
  int iterations = 10;
  /// The most steps of the global solve a pass falls back on when the sweeps leave a spring
  /// beyond its bound (fast projection, Goldenthal et al. 2007); 0 switches it off.
  int projection_iterations = 10;
  /// Positions projected onto the bounds (Provot 1995; Fuhrmann et al. 2003 for compression).
  bool position_correction = true;
  /// Velocities along springs at a bound filtered so they do not move past it (Vassilev,
  /// Spanlang & Chrysanthou 2001).
  bool velocity_correction = true;
};

/// How far past its bound a spring may be left, relative to the bound's strain: a 10 % limit
/// holds to 10.1 %.
inline constexpr Real kStretchTolerance = 0.01;

/// The bounds of a limit as factors of the rest length.
struct StretchBounds {
  Real max_factor;  ///< 1 + max strain
  Real min_factor;  ///< 1 − max compression; 0 when off
  Real max_slack;   ///< lengths up to max_factor + max_slack (times rest) count as held
  Real min_slack;

  static StretchBounds of(const StretchLimit& limit) {
    const bool compression = limit.max_compression >= 0;
    return {1 + limit.max_strain, compression ? 1 - limit.max_compression : 0,
            kStretchTolerance * limit.max_strain,
            compression ? kStretchTolerance * limit.max_compression : 0};
  }
};

/// What one pass did.
struct StretchLimitStats {
  int position_sweeps = 0;
  int position_projections = 0;  ///< steps of the global solve after the sweeps
  int velocity_sweeps = 0;
  bool velocity_solved_together = false;  ///< the velocity filter solved as one system
};

/// The limiter of one cloth: keeps the cloth's long range attachments, worked out again when
/// its pinned particles change.
class StretchLimiter {
 public:
  /// Applies the enabled corrections to `state` after a (sub)step of length h. Pinned particles
  /// (inverse mass 0) never move: the other end moves the whole way instead (Provot).
  StretchLimitStats apply(const ClothModel& model, std::span<const Real> inv_mass,
                          const StretchLimit& limit, Real h, ParticleState& state);

  /// Whether colliders moved the cloth's particles after the last pass. While they do, the
  /// colliders push the cloth past its limit again after every pass, so the limiter does less:
  /// the sweeps stop once they stall, and the fast projection is not tried. Eight proxies
  /// pressed into the served cloth: 0.73 ms of limiting a step instead of 4.3, and a largest
  /// strain after a step of 0.1039 instead of 0.1026 (docs/results/cloth.md section 4).
  void set_pushed_by_colliders(bool pushed) { pushed_by_colliders_ = pushed; }

 private:
  void update_attachments(const ClothModel& model, std::span<const Real> inv_mass);

  /// Fast projection (Goldenthal et al. 2007, §4) of the springs beyond their bounds: Newton
  /// steps onto C_k = |x_j − x_i| − bound_k = 0 for those springs, taken again at each step,
  /// until none is beyond its bound by more than half the slack, or `max_iterations`. Returns
  /// the steps taken.
  int project_together(const ClothModel& model, std::span<const Real> inv_mass,
                       const StretchBounds& b, int max_iterations, ParticleState& state);

  /// The velocity filter solved for all springs at once, when one of them at its bound moves
  /// past it by more than the slack in a step of h, or `always`: every spring at a bound loses
  /// its ends' relative velocity along it, by the change of least kinetic energy that does so
  /// (which only removes energy). Returns whether it solved.
  bool filter_together(const ClothModel& model, std::span<const Real> inv_mass,
                       const StretchBounds& b, Real h, bool always, ParticleState& state);

  std::vector<std::uint32_t> pinned_;  ///< the pinned particles the attachments were made for
  std::vector<std::uint32_t> scratch_pinned_;  ///< the pinned particles now, compared with pinned_
  std::vector<Attachment> attachments_;
  bool attachments_valid_ = false;
  SpringConstraintSolve solve_;
  std::vector<std::uint32_t> active_;  ///< the springs of a global solve
  std::vector<Real> residual_;         ///< their C_k, or their velocities apart
  std::vector<std::int8_t> held_;  ///< per spring: held at its upper bound (1), lower (−1), not
  bool pushed_by_colliders_ = false;
};

}  // namespace felt
