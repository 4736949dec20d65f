#include "core/cloth/stretch_limiter.hpp"

#include <algorithm>

namespace felt {
namespace {

struct Bounds {
  Real max_factor;  ///< 1 + max strain
  Real min_factor;  ///< 1 − max compression; 0 when off
  Real max_slack;   ///< lengths up to max_factor + max_slack (times rest) count as held
  Real min_slack;
};

Bounds bounds_of(const StretchLimit& limit) {
  const bool compression = limit.max_compression >= 0;
  return {1 + limit.max_strain, compression ? 1 - limit.max_compression : 0,
          kStretchTolerance * limit.max_strain,
          compression ? kStretchTolerance * limit.max_compression : 0};
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
/// the slack, or `max_sweeps`: the other half is for the corrections later in that sweep, which
/// may lengthen a spring already checked. Each spring out of bounds is set to its bound, its ends
/// moving in proportion to their inverse masses (about the midpoint for equal masses; the free end
/// the whole way when the other is pinned), which keeps their centre of mass. Returns the sweeps
/// taken.
int project_springs(const ClothModel& model, std::span<const Real> inv_mass, const Bounds& b,
                    int max_sweeps, ParticleState& state) {
  int sweep = 0;
  bool out_of_bounds = true;
  while (out_of_bounds && sweep < max_sweeps) {
    out_of_bounds = false;
    sweep_springs(model, sweep, [&](const Spring& s) {
      const Vec3 d = state.x[s.j] - state.x[s.i];
      const Real length = d.norm();
      Real target;
      if (length > b.max_factor * s.rest_length) {
        target = b.max_factor * s.rest_length;
        out_of_bounds |= length > (b.max_factor + 0.5 * b.max_slack) * s.rest_length;
      } else if (length < b.min_factor * s.rest_length && length > 0) {
        target = b.min_factor * s.rest_length;
        out_of_bounds |= length < (b.min_factor - 0.5 * b.min_slack) * s.rest_length;
      } else {
        return;
      }
      const Real wi = inv_mass[s.i], wj = inv_mass[s.j];
      if (wi + wj == 0) return;
      const Vec3 excess = (length - target) / (length * (wi + wj)) * d;
      state.x[s.i] += wi * excess;
      state.x[s.j] -= wj * excess;
    });
    ++sweep;
  }
  return sweep;
}

/// Removes the velocity of particles moving away from the pin of a taut attachment.
void filter_attachment_velocities(std::span<const Attachment> attachments, Real max_factor,
                                  Real slack, ParticleState& state) {
  for (const Attachment& a : attachments) {
    const Vec3 d = state.x[a.particle] - state.x[a.pin];
    const Real length = d.norm();
    if (length < (max_factor - slack) * a.path_length || length == 0) continue;
    const Vec3 dir = d / length;
    const Real away = (state.v[a.particle] - state.v[a.pin]).dot(dir);
    if (away > 0) state.v[a.particle] -= away * dir;
  }
}

/// Vassilev et al. 2001, eq. (4.27) of thesis 1, one-sided: the ends of a spring at a bound that
/// move past it get the same velocity component along it, their mass-weighted average (a pinned
/// end imposes its own), which conserves momentum and takes kinetic energy away, never adds it.
/// A spring counts as at its bound within the slack. Gauss–Seidel, until the largest velocity
/// removed in a sweep would move a spring by less than the slack in a step of h, or `max_sweeps`.
/// Returns the sweeps taken.
int filter_spring_velocities(const ClothModel& model, std::span<const Real> inv_mass,
                             const Bounds& b, Real h, int max_sweeps, ParticleState& state) {
  int sweep = 0;
  bool moving_past = true;
  while (moving_past && sweep < max_sweeps) {
    moving_past = false;
    sweep_springs(model, sweep, [&](const Spring& s) {
      const Vec3 d = state.x[s.j] - state.x[s.i];
      const Real length = d.norm();
      // +1: the spring may not lengthen (at the upper bound); −1: not shorten; 0: free
      Real side = 0;
      Real slack = 0;
      if (length >= (b.max_factor - b.max_slack) * s.rest_length) {
        side = 1;
        slack = b.max_slack;
      } else if (length <= (b.min_factor + b.min_slack) * s.rest_length) {
        side = -1;
        slack = b.min_slack;
      }
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
  return sweep;
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

StretchLimitStats StretchLimiter::apply(const ClothModel& model, std::span<const Real> inv_mass,
                                        const StretchLimit& limit, Real h, ParticleState& state) {
  StretchLimitStats stats;
  if (!limit.enabled) return stats;
  const Bounds b = bounds_of(limit);
  update_attachments(model, inv_mass);
  if (limit.position_correction) {
    project_attachments(attachments_, b.max_factor, state);
    stats.position_sweeps = project_springs(model, inv_mass, b, limit.iterations, state);
  }
  if (limit.velocity_correction) {
    filter_attachment_velocities(attachments_, b.max_factor, b.max_slack, state);
    stats.velocity_sweeps =
        filter_spring_velocities(model, inv_mass, b, h, limit.iterations, state);
  }
  return stats;
}

}  // namespace felt
