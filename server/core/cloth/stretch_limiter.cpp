#include "core/cloth/stretch_limiter.hpp"

namespace felt {
namespace {

bool limited(const Spring& s) {
  return s.kind != SpringKind::kBend && s.rest_length > 0;
}

/// Vassilev, Spanlang & Chrysanthou 2001, eq. (4.27) of thesis 1: the components of both
/// velocities along a too-long spring are replaced by their (mass-weighted) average.
void correct_velocities(const ClothModel& model, std::span<const Real> inv_mass,
                        Real max_length_factor, ParticleState& state) {
  for (const Spring& s : model.springs) {
    if (!limited(s)) continue;
    const Vec3 d = state.x[s.j] - state.x[s.i];
    const Real length = d.norm();
    if (length <= max_length_factor * s.rest_length) continue;
    const Real wi = inv_mass[s.i], wj = inv_mass[s.j];
    if (wi + wj == 0) continue;
    const Vec3 dir = d / length;
    const Real vi = state.v[s.i].dot(dir), vj = state.v[s.j].dot(dir);
    // the common speed conserves momentum; a pinned end (w = 0) imposes its own speed
    const Real common = (wj * vi + wi * vj) / (wi + wj);
    state.v[s.i] += (common - vi) * dir;
    state.v[s.j] += (common - vj) * dir;
  }
}

}  // namespace

int limit_stretch(const ClothModel& model, std::span<const Real> inv_mass,
                  const StretchLimit& limit, Real h, ParticleState& state) {
  if (!limit.enabled) return 0;
  const Real max_factor = 1 + limit.max_strain;
  // off (negative): a factor of 0 that no length is below
  const Real min_factor = limit.max_compression < 0 ? 0 : 1 - limit.max_compression;
  if (limit.velocity_correction) correct_velocities(model, inv_mass, max_factor, state);
  if (!limit.position_correction) return 0;

  int sweep = 0;
  while (sweep < limit.iterations) {
    ++sweep;
    bool any = false;
    for (const Spring& s : model.springs) {
      if (!limited(s)) continue;
      const Vec3 d = state.x[s.j] - state.x[s.i];
      const Real length = d.norm();
      // Provot 1995 shortens to s_max r; Fuhrmann et al. 2003 also lengthens to s_min r
      Real target = max_factor * s.rest_length;
      if (length <= target) {
        target = min_factor * s.rest_length;
        if (length >= target || length == 0) continue;
      }
      const Real wi = inv_mass[s.i], wj = inv_mass[s.j];
      if (wi + wj == 0) continue;
      any = true;
      // about the midpoint, or toward the fixed end; with unequal masses the lighter end moves
      // more (the same point when masses are equal)
      const Vec3 excess = (length - target) / length * d;
      const Vec3 move_i = wi / (wi + wj) * excess;
      const Vec3 move_j = -wj / (wi + wj) * excess;
      state.x[s.i] += move_i;
      state.x[s.j] += move_j;
      // v = (x(t+h) − x(t))/h follows the corrected position (the thesis prints '+': a typo)
      state.v[s.i] += move_i / h;
      state.v[s.j] += move_j / h;
    }
    if (!any) break;
  }
  return sweep;
}

}  // namespace felt
