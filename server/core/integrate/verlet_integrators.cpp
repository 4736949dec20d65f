#include "core/integrate/verlet_integrators.hpp"

#include <limits>

namespace felt {
namespace {

/// Marks the history of a pinned particle as absent: NaN equals nothing, so the particle
/// restarts with the exact start formula should it be unpinned.
const Vec3 kNoHistory = Vec3::Constant(std::numeric_limits<Real>::quiet_NaN());

}  // namespace

void PositionVerlet::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  if (!(h > 0)) return;  // nothing to advance, and h/h_prev, (x_new − x)/h would be 0/0
  const std::size_t n = state.size();
  if (x_prev_.size() != n) {
    x_prev_.resize(n);
    v_out_.resize(n);
    h_prev_ = 0;  // another body shape: no usable history
  }
  force_.resize(n);
  // state.v is v(t) + O(h²) (see the header), good enough for velocity-dependent forces
  system.compute_forces(state.x, state.v, t, force_);
  const auto inv_mass = system.inv_mass();
  const bool start = h_prev_ == 0;
  const Real h_prev = start ? h : h_prev_;
  // x_new = x + (x − x_prev) h/h_prev + ½h(h + h_prev) a: time-corrected Verlet (Dummer 2005)
  // with the uneven-grid acceleration term, see the header
  const Real ratio = h / h_prev;
  const Real accel_scale = 0.5 * h * (h + h_prev);
  for (std::size_t p = 0; p < n; ++p) {
    const Vec3 x = state.x[p];
    if (inv_mass[p] == 0) {
      state.v[p].setZero();
      v_out_[p] = kNoHistory;
      continue;
    }
    const Vec3 a = inv_mass[p] * force_[p];
    if (start || state.v[p] != v_out_[p]) {
      // x_prev = x − h_prev v + ½h_prev² a makes this step the Taylor step x + h v + ½h² a
      x_prev_[p] = x - h_prev * state.v[p] + 0.5 * h_prev * h_prev * a;
    }
    const Vec3 x_new = x + ratio * (x - x_prev_[p]) + accel_scale * a;
    x_prev_[p] = x;
    state.x[p] = x_new;
    // backward difference plus half a step of acceleration: v(t+h) + O(h²)
    state.v[p] = (x_new - x) / h + 0.5 * h * a;
    v_out_[p] = state.v[p];
  }
  h_prev_ = h;
}

void VelocityVerlet::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const std::size_t n = state.size();
  if (force_.size() != n) {
    force_.resize(n);
    v_predicted_.resize(n);
    x_out_.resize(n);
    v_out_.resize(n);
    force_valid_ = false;
  }
  // the kept force is f(t) only if nobody moved the state since the last step
  bool valid = force_valid_;
  for (std::size_t p = 0; valid && p < n; ++p) {
    valid = state.x[p] == x_out_[p] && state.v[p] == v_out_[p];
  }
  if (!valid) system.compute_forces(state.x, state.v, t, force_);
  const auto inv_mass = system.inv_mass();
  // thesis 1 §4.5: v(t+½h) = v + ½h a(t), x(t+h) = x + h v(t+½h)
  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) {
      state.v[p].setZero();
      v_predicted_[p].setZero();
      continue;
    }
    const Vec3 half_kick = 0.5 * h * inv_mass[p] * force_[p];
    state.v[p] += half_kick;
    state.x[p] += h * state.v[p];
    v_predicted_[p] = state.v[p] + half_kick;  // v + h a(t) = v(t+h) + O(h²)
  }
  system.compute_forces(state.x, v_predicted_, t + h, force_);
  // v(t+h) = v(t+½h) + ½h a(t+h); a pinned particle gains 0 · f
  for (std::size_t p = 0; p < n; ++p) {
    state.v[p] += 0.5 * h * inv_mass[p] * force_[p];
    x_out_[p] = state.x[p];
    v_out_[p] = state.v[p];
  }
  force_valid_ = true;
}

void Leapfrog::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  if (!(h > 0)) return;  // nothing to advance; the half-step velocity stays valid
  const std::size_t n = state.size();
  if (offset_.size() != n) {
    offset_.resize(n);
    h_prev_ = 0;
  }
  force_.resize(n);
  // state.v is v(t) + O(h²), good enough for velocity-dependent forces
  system.compute_forces(state.x, state.v, t, force_);
  const auto inv_mass = system.inv_mass();
  const bool start = h_prev_ == 0;
  // the kick spans from t − ½h_prev to t + ½h
  const Real kick = 0.5 * (h_prev_ + h);
  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) {
      offset_[p] = kNoHistory;
      state.v[p].setZero();
      continue;
    }
    const Vec3 a = inv_mass[p] * force_[p];
    // the internal half-step velocity: v(t) + ½h a(t) at the start (or just unpinned), else
    // v(t−½h_prev) + ½(h_prev + h) a(t)
    const Vec3 v_half = start || offset_[p].hasNaN() ? Vec3(state.v[p] + 0.5 * h * a)
                                                     : Vec3(state.v[p] - offset_[p] + kick * a);
    state.x[p] += h * v_half;  // drift
    offset_[p] = 0.5 * h * a;
    state.v[p] = v_half + offset_[p];  // v(t+h) + O(h²)
  }
  h_prev_ = h;
}

}  // namespace felt
