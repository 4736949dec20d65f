#include "core/cloth/stretch_limiter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace felt {
namespace {

/// The length a spring beyond one of its bounds is set to, and whether it is beyond it by more
/// than half the slack (see project_springs); nothing when it is within its bounds.
struct Excess {
  Real target;
  bool beyond_slack;
};

std::optional<Excess> excess_of(const Spring& s, Real length, const StretchBounds& b) {
  if (length > b.max_factor * s.rest_length) {
    return Excess{b.max_factor * s.rest_length,
                  length > (b.max_factor + 0.5 * b.max_slack) * s.rest_length};
  }
  if (length < b.min_factor * s.rest_length && length > 0) {
    return Excess{b.min_factor * s.rest_length,
                  length < (b.min_factor - 0.5 * b.min_slack) * s.rest_length};
  }
  return std::nullopt;
}

/// Whether a spring is at one of its bounds (within the slack): +1 at the upper bound (it may
/// not lengthen), −1 at the lower (it may not shorten), 0 when free, with that bound's slack.
std::pair<Real, Real> side_of(const Spring& s, Real length, const StretchBounds& b) {
  if (length >= (b.max_factor - b.max_slack) * s.rest_length) return {1, b.max_slack};
  if (length <= (b.min_factor + b.min_slack) * s.rest_length) return {-1, b.min_slack};
  return {0, 0};
}

/// Visits the springs forward on even sweeps and backward on odd ones: alternating the order
/// lets a correction travel both ways through the cloth within two sweeps (symmetric
/// Gauss–Seidel).
template <class Visit>
void sweep_springs(const ClothModel& model, int sweep, Visit&& visit) {
  const std::size_t n = model.springs.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Spring& s = model.springs[sweep % 2 == 0 ? k : n - 1 - k];
    if (is_limited(s)) visit(s);
  }
}

/// Projects the free particles onto their attachments' balls (the pin does not move).
void project_attachments(std::span<const Attachment> attachments, Real max_factor,
                         ParticleState& state) {
  for (const Attachment& a : attachments) {
    const Vec3 d = state.x[a.particle] - state.x[a.pin];
    const Real length = d.norm();
    const Real bound = max_factor * a.path_length;
    if (length > bound) state.x[a.particle] = state.x[a.pin] + (bound / length) * d;
  }
}

/// Gauss–Seidel over the springs until a sweep finds none beyond its bound by more than half
/// the slack, or `max_sweeps`, or, when `stop_when_stalled`, a sweep that leaves its largest
/// excess above kStalledSweep of the one before. The other half of the slack is for the
/// corrections later in that sweep, which may lengthen a spring already checked. Each spring out
/// of bounds is set to its bound, its ends moving in proportion to their inverse masses (about
/// the midpoint for equal masses; the free end the whole way when the other is pinned), which
/// keeps their centre of mass. Returns the sweeps taken and whether the last found none beyond.
std::pair<int, bool> project_springs(const ClothModel& model, std::span<const Real> inv_mass,
                                     const StretchBounds& b, int max_sweeps, bool stop_when_stalled,
                                     ParticleState& state) {
  // A taut cloth pressed by colliders: a correction travels on through the cloth, each sweep
  // takes a few per cent off the excess (0.0058, 0.0037, 0.0034, ... of the rest length, eight
  // balls pressed into the served cloth) at the cost of a pass over every spring, and the
  // colliders push the cloth back after the pass anyway. (Without them the sweeps go on: a
  // badly stretched cloth needs hundreds, each taking 1 % off, and the fast projection after
  // them diverges from so far away.)
  constexpr Real kStalledSweep = 0.5;
  int sweep = 0;
  bool out_of_bounds = true;
  Real previous_excess = std::numeric_limits<Real>::infinity();
  while (out_of_bounds && sweep < max_sweeps) {
    out_of_bounds = false;
    Real largest_excess = 0;
    sweep_springs(model, sweep, [&](const Spring& s) {
      const Vec3 d = state.x[s.j] - state.x[s.i];
      const Real length = d.norm();
      const std::optional<Excess> e = excess_of(s, length, b);
      if (!e) return;
      out_of_bounds |= e->beyond_slack;
      const Real wi = inv_mass[s.i], wj = inv_mass[s.j];
      if (wi + wj == 0) return;
      largest_excess = std::max(largest_excess, std::abs(length - e->target) / s.rest_length);
      const Vec3 excess = (length - e->target) / (length * (wi + wj)) * d;
      state.x[s.i] += wi * excess;
      state.x[s.j] -= wj * excess;
    });
    ++sweep;
    if (stop_when_stalled && largest_excess > kStalledSweep * previous_excess) break;
    previous_excess = largest_excess;
  }
  return {sweep, !out_of_bounds};
}

/// Removes the velocity along a taut attachment, towards its pin as well as away: a taut
/// attachment is held at its bound for the step, like a spring in the global filter. One-sided,
/// xpbd's single projection pass left particles by the pins with a velocity towards them that
/// the position correction took back every step without touching it, and the cloth never came
/// to rest (docs/results/cloth.md, section 4). Removing a component only takes energy away.
void filter_attachment_velocities(std::span<const Attachment> attachments, Real max_factor,
                                  Real slack, ParticleState& state) {
  for (const Attachment& a : attachments) {
    const Vec3 d = state.x[a.particle] - state.x[a.pin];
    const Real length = d.norm();
    if (length < (max_factor - slack) * a.path_length || length == 0) continue;
    const Vec3 dir = d / length;
    const Real away = (state.v[a.particle] - state.v[a.pin]).dot(dir);
    if (away != 0) state.v[a.particle] -= away * dir;
  }
}

/// Vassilev et al. 2001, eq. (4.27) of thesis 1, one-sided: the ends of a spring at a bound that
/// move past it get the same velocity component along it, their mass-weighted average (a pinned
/// end imposes its own), which conserves momentum and takes kinetic energy away, never adds it.
/// A spring counts as at its bound within the slack. Gauss–Seidel, until the largest velocity
/// removed in a sweep would move a spring by less than the slack in a step of h, or `max_sweeps`.
/// Returns the sweeps taken and whether the last found no spring moving past its bound.
std::pair<int, bool> filter_spring_velocities(const ClothModel& model,
                                              std::span<const Real> inv_mass,
                                              const StretchBounds& b, Real h, int max_sweeps,
                                              ParticleState& state) {
  int sweep = 0;
  bool moving_past = true;
  while (moving_past && sweep < max_sweeps) {
    moving_past = false;
    sweep_springs(model, sweep, [&](const Spring& s) {
      const Vec3 d = state.x[s.j] - state.x[s.i];
      const Real length = d.norm();
      const auto [side, slack] = side_of(s, length, b);
      if (side == 0 || length == 0) return;
      const Real wi = inv_mass[s.i], wj = inv_mass[s.j];
      if (wi + wj == 0) return;
      const Vec3 dir = d / length;
      const Real vi = state.v[s.i].dot(dir), vj = state.v[s.j].dot(dir);
      const Real separating = side * (vj - vi);
      if (separating <= 0) return;
      const Real common = (wj * vi + wi * vj) / (wi + wj);
      state.v[s.i] += (common - vi) * dir;
      state.v[s.j] += (common - vj) * dir;
      moving_past |= separating * h > slack * s.rest_length;
    });
    ++sweep;
  }
  return {sweep, !moving_past};
}

}  // namespace

void StretchLimiter::update_attachments(const ClothModel& model, std::span<const Real> inv_mass) {
  // rebuilt only when the pinned particles change: pins are few and rarely moved
  std::vector<std::uint32_t>& pinned = scratch_pinned_;
  pinned.clear();
  for (std::uint32_t p = 0; p < inv_mass.size(); ++p) {
    if (inv_mass[p] == 0) pinned.push_back(p);
  }
  if (attachments_valid_ && pinned == pinned_) return;
  pinned_.swap(pinned);
  attachments_ = long_range_attachments(model, inv_mass);
  attachments_valid_ = true;
}

int StretchLimiter::project_together(const ClothModel& model, std::span<const Real> inv_mass,
                                     const StretchBounds& b, int max_iterations,
                                     ParticleState& state) {
  // the springs held so far stay held at their bound for the rest of the pass: a Newton step
  // pulls other springs past their bounds, and letting those that came back below go again
  // made the set alternate without converging
  held_.assign(model.springs.size(), 0);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    active_.clear();
    residual_.clear();
    bool out_of_bounds = false;
    for (std::uint32_t k = 0; k < model.springs.size(); ++k) {
      const Spring& s = model.springs[k];
      if (!is_limited(s) || inv_mass[s.i] + inv_mass[s.j] == 0) continue;
      const Real length = (state.x[s.j] - state.x[s.i]).norm();
      const std::optional<Excess> e = excess_of(s, length, b);
      if (e) {
        out_of_bounds |= e->beyond_slack;
        held_[k] = length > s.rest_length ? 1 : -1;
      } else if (iteration == 0) {
        held_[k] = static_cast<std::int8_t>(side_of(s, length, b).first);
      }
      if (held_[k] == 0) continue;
      active_.push_back(k);
      residual_.push_back(length - (held_[k] > 0 ? b.max_factor : b.min_factor) * s.rest_length);
    }
    if (!out_of_bounds || !solve_.factorize(model, inv_mass, active_, state.x)) return iteration;
    solve_.correct(model, inv_mass,
                   Eigen::Map<const Eigen::VectorXd>(residual_.data(), std::ssize(residual_)),
                   state.x);
  }
  return max_iterations;
}

bool StretchLimiter::filter_together(const ClothModel& model, std::span<const Real> inv_mass,
                                     const StretchBounds& b, Real h, bool always,
                                     ParticleState& state) {
  // every spring at its bound is in the set, those whose ends approach each other too: with
  // only the springs moving past their bounds, each solve set the next ones moving and the
  // set grew by a few springs a solve (no rest after 10 solves a pass on a cloth hung from two
  // corners). A spring stopped from slackening starts again in the next step.
  active_.clear();
  residual_.clear();
  bool moving_past = false;
  for (std::uint32_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
    if (!is_limited(s) || inv_mass[s.i] + inv_mass[s.j] == 0) continue;
    const Vec3 d = state.x[s.j] - state.x[s.i];
    const Real length = d.norm();
    const auto [side, slack] = side_of(s, length, b);
    if (side == 0 || length == 0) continue;
    const Real apart = (state.v[s.j] - state.v[s.i]).dot(d) / length;
    moving_past |= side * apart * h > slack * s.rest_length;
    active_.push_back(k);
    residual_.push_back(apart);
  }
  if (!(moving_past || always) || !solve_.factorize(model, inv_mass, active_, state.x))
    return false;
  solve_.correct(model, inv_mass,
                 Eigen::Map<const Eigen::VectorXd>(residual_.data(), std::ssize(residual_)),
                 state.v);
  return true;
}

StretchLimitStats StretchLimiter::apply(const ClothModel& model, std::span<const Real> inv_mass,
                                        const StretchLimit& limit, Real h, ParticleState& state) {
  StretchLimitStats stats;
  if (!limit.enabled) return stats;
  const StretchBounds b = StretchBounds::of(limit);
  update_attachments(model, inv_mass);
  if (limit.position_correction) {
    project_attachments(attachments_, b.max_factor, state);
    const auto [sweeps, held] =
        project_springs(model, inv_mass, b, limit.iterations, pushed_by_colliders_, state);
    stats.position_sweeps = sweeps;
    if (!held && !pushed_by_colliders_) {
      stats.position_projections =
          project_together(model, inv_mass, b, limit.projection_iterations, state);
    }
  }
  if (limit.velocity_correction) {
    filter_attachment_velocities(attachments_, b.max_factor, b.max_slack, state);
    // after a global projection of the positions the velocities are filtered globally too:
    // Gauss–Seidel sweeps that stopped by their tolerance still left a cloth hung from two
    // corners cycling between the same three states (a lift by the projection every step)
    if (stats.position_projections > 0) {
      stats.velocity_solved_together = filter_together(model, inv_mass, b, h, true, state);
    } else {
      const auto [sweeps, stopped] =
          filter_spring_velocities(model, inv_mass, b, h, limit.iterations, state);
      stats.velocity_sweeps = sweeps;
      if (!stopped && limit.projection_iterations > 0) {
        stats.velocity_solved_together = filter_together(model, inv_mass, b, h, false, state);
      }
    }
  }
  return stats;
}

}  // namespace felt
