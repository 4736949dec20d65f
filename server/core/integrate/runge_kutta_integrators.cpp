#include "core/integrate/runge_kutta_integrators.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>

#include "core/math/check.hpp"

namespace felt {
namespace {

/// Sizes scratch buffers; resize() to the size they already have allocates nothing.
template <typename... Buffers>
void size_buffers(std::size_t n, Buffers&... buffers) {
  (buffers.resize(n), ...);
}

/// The state derivative F(X) = [v, M⁻¹ f(x, v, t)] of thesis 1 §4.1, written into (dx, dv).
/// A pinned particle (inverse mass 0) gets F = 0 so that it cannot drift even if it was pinned
/// while moving.
void derivative(const DynamicSystem& system, std::span<const Vec3> x, std::span<const Vec3> v,
                Real t, std::span<Vec3> dx, std::span<Vec3> dv) {
  system.compute_forces(x, v, t, dv);
  const auto inv_mass = system.inv_mass();
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (inv_mass[p] == 0) {
      dx[p].setZero();
      dv[p].setZero();
    } else {
      dx[p] = v[p];
      dv[p] *= inv_mass[p];
    }
  }
}

// Dormand–Prince 5(4), Hairer, Nørsett & Wanner, Solving ODEs I (2nd ed.), Table 5.2.
constexpr std::array<Real, AdaptiveRungeKutta::kStages> kC{0,       1.0 / 5, 3.0 / 10, 4.0 / 5,
                                                           8.0 / 9, 1,       1};
constexpr std::array<std::array<Real, AdaptiveRungeKutta::kStages - 1>, AdaptiveRungeKutta::kStages>
    kA{{
        {},
        {1.0 / 5},
        {3.0 / 40, 9.0 / 40},
        {44.0 / 45, -56.0 / 15, 32.0 / 9},
        {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
        {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
        // the fifth-order weights b: the last stage is evaluated at the new state (FSAL)
        {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84},
    }};
// b − b̂, with the fourth-order weights b̂ = (5179/57600, 0, 7571/16695, 393/640,
// −92097/339200, 187/2100, 1/40)
constexpr std::array<Real, AdaptiveRungeKutta::kStages> kE{
    71.0 / 57600, 0, -71.0 / 16695, 71.0 / 1920, -17253.0 / 339200, 22.0 / 525, -1.0 / 40};

// Step-size control, HNW I §II.4 (4.13): h_new = h · min(max, max(min, safety · err^(−1/5))),
// the exponent 1/(q+1) with q = 4 the order of the embedded solution.
constexpr Real kSafety = 0.9;
constexpr Real kMinFactor = 0.2;
constexpr Real kMaxFactor = 5;

}  // namespace

Real Midpoint::step_limit(const OscillatorMode& mode) const {
  static constexpr std::array<Real, 3> kStabilityPolynomial{1, 1, 1.0 / 2};
  return polynomial_step_limit(kStabilityPolynomial, mode);
}

void Midpoint::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const std::size_t n = state.size();
  size_buffers(n, dx_, dv_, x_mid_, v_mid_);
  // thesis 1 §4.2: X(t+h) = X + h F(X + ½h F(X))
  derivative(system, state.x, state.v, t, dx_, dv_);
  for (std::size_t p = 0; p < n; ++p) {
    x_mid_[p] = state.x[p] + 0.5 * h * dx_[p];
    v_mid_[p] = state.v[p] + 0.5 * h * dv_[p];
  }
  derivative(system, x_mid_, v_mid_, t + 0.5 * h, dx_, dv_);
  const auto inv_mass = system.inv_mass();
  for (std::size_t p = 0; p < n; ++p) {
    state.x[p] += h * dx_[p];
    state.v[p] = inv_mass[p] == 0 ? Vec3(Vec3::Zero()) : Vec3(state.v[p] + h * dv_[p]);
  }
}

Real RungeKutta4::step_limit(const OscillatorMode& mode) const {
  static constexpr std::array<Real, 5> kStabilityPolynomial{1, 1, 1.0 / 2, 1.0 / 6, 1.0 / 24};
  return polynomial_step_limit(kStabilityPolynomial, mode);
}

void RungeKutta4::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const std::size_t n = state.size();
  size_buffers(n, dx_, dv_, x_stage_, v_stage_, dx_sum_, dv_sum_);
  // thesis 1 §4.2: k1 = F(X), k2 = F(X + ½h k1), k3 = F(X + ½h k2), k4 = F(X + h k3),
  // X(t+h) = X + h (k1 + 2 k2 + 2 k3 + k4)/6; the sums accumulate k1 + 2 k2 + 2 k3
  // stage s evaluates at t + offset[s]·h and enters the sum with weight[s]
  constexpr Real kOffset[] = {0, 0.5, 0.5, 1};
  constexpr Real kWeight[] = {1, 2, 2};
  for (int stage = 0; stage < 3; ++stage) {
    if (stage == 0) {
      derivative(system, state.x, state.v, t, dx_, dv_);
    } else {
      derivative(system, x_stage_, v_stage_, t + kOffset[stage] * h, dx_, dv_);
    }
    const Real next = kOffset[stage + 1] * h;
    for (std::size_t p = 0; p < n; ++p) {
      dx_sum_[p] = (stage == 0 ? Vec3(Vec3::Zero()) : dx_sum_[p]) + kWeight[stage] * dx_[p];
      dv_sum_[p] = (stage == 0 ? Vec3(Vec3::Zero()) : dv_sum_[p]) + kWeight[stage] * dv_[p];
      x_stage_[p] = state.x[p] + next * dx_[p];
      v_stage_[p] = state.v[p] + next * dv_[p];
    }
  }
  derivative(system, x_stage_, v_stage_, t + h, dx_, dv_);
  const auto inv_mass = system.inv_mass();
  for (std::size_t p = 0; p < n; ++p) {
    state.x[p] += h / 6 * (dx_sum_[p] + dx_[p]);
    state.v[p] =
        inv_mass[p] == 0 ? Vec3(Vec3::Zero()) : Vec3(state.v[p] + h / 6 * (dv_sum_[p] + dv_[p]));
  }
}

Real AdaptiveRungeKutta::internal_step_limit(const OscillatorMode& mode) const {
  static constexpr std::array<Real, 7> kStabilityPolynomial{1,        1,         1.0 / 2,  1.0 / 6,
                                                            1.0 / 24, 1.0 / 120, 1.0 / 600};
  return polynomial_step_limit(kStabilityPolynomial, mode);
}

AdaptiveRungeKutta::AdaptiveRungeKutta(Real tolerance, int max_internal_steps)
    : tolerance_(tolerance), max_internal_steps_(max_internal_steps) {
  FELT_CHECK(tolerance > 0);
  FELT_CHECK(max_internal_steps >= 1);
}

void AdaptiveRungeKutta::evaluate_stage(const DynamicSystem& system, const ParticleState& state,
                                        int s, Real t, Real dt) {
  for (std::size_t p = 0; p < state.size(); ++p) {
    Vec3 x = state.x[p];
    Vec3 v = state.v[p];
    for (int j = 0; j < s; ++j) {
      x += dt * kA[s][j] * dx_[j][p];
      v += dt * kA[s][j] * dv_[j][p];
    }
    x_stage_[p] = x;
    v_stage_[p] = v;
  }
  derivative(system, x_stage_, v_stage_, t + kC[s] * dt, dx_[s], dv_[s]);
}

void AdaptiveRungeKutta::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  if (!(h > 0)) return;  // nothing to advance; the kept step size stays
  const std::size_t n = state.size();
  for (int s = 0; s < kStages; ++s) size_buffers(n, dx_[s], dv_[s]);
  size_buffers(n, x_stage_, v_stage_);
  const auto inv_mass = system.inv_mass();

  Real trial = internal_step_ > 0 ? std::min(internal_step_, h) : h;
  Real done = 0;
  int taken = 0;
  int rejected = 0;
  bool capped = false;
  const int max_steps = std::min(max_internal_steps_, internal_step_cap_);
  // the first stage of the first internal step; later ones reuse the last stage (FSAL). Not
  // kept between calls: the forces may change in between (external forces, pins).
  derivative(system, state.x, state.v, t, dx_[0], dv_[0]);
  while (true) {
    const Real remaining = h - done;
    // the budget: with k internal steps left, none may be shorter than remaining / k
    const Real smallest = remaining / (max_steps - taken);
    Real dt = std::max(trial, smallest);
    bool last = false;
    if (dt * 1.01 >= remaining) {
      // stretch by up to 1% rather than leave a sliver to the end (as HNW's DOPRI5 does)
      dt = remaining;
      last = true;
    } else if (dt * 2 > remaining) {
      dt = remaining / 2;  // two even steps rather than a long one and a short one
    }
    const bool forced = dt <= smallest;  // the smallest step allowed cannot be rejected

    const Real t0 = t + done;
    for (int s = 1; s < kStages; ++s) evaluate_stage(system, state, s, t0, dt);
    // x_stage_, v_stage_ now hold the fifth-order solution at t0 + dt
    Real worst_sq = 0;  // largest squared position error estimate, over dt²
    for (std::size_t p = 0; p < n; ++p) {
      Vec3 e = Vec3::Zero();
      for (int s = 0; s < kStages; ++s) e += kE[s] * dx_[s][p];
      worst_sq = std::max(worst_sq, e.squaredNorm());
    }
    // HNW I (4.11) with the max norm over particles and sc = tolerance (absolute only)
    const Real error = dt * std::sqrt(worst_sq) / tolerance_;
    ++taken;

    Real factor = error > 0 ? kSafety * std::pow(error, Real{-0.2}) : kMaxFactor;
    if (!(factor >= kMinFactor)) factor = kMinFactor;  // also a NaN error: shrink
    factor = std::min(factor, kMaxFactor);

    if (error <= 1 || forced) {
      capped = capped || !(error <= 1);
      for (std::size_t p = 0; p < n; ++p) {
        state.x[p] = x_stage_[p];
        state.v[p] = inv_mass[p] == 0 ? Vec3(Vec3::Zero()) : v_stage_[p];
      }
      std::swap(dx_[0], dx_[kStages - 1]);
      std::swap(dv_[0], dv_[kStages - 1]);
      const Real proposal = dt * factor;
      // a step cut short to land on t + h says nothing against the longer one it replaced
      trial = dt < trial ? std::max(trial, proposal) : proposal;
      if (last) break;
      done += dt;
    } else {
      ++rejected;
      trial = dt * factor;  // factor < 1 here since error > 1
    }
  }
  // larger than h is never used, and an error-free system (free fall) would otherwise grow it
  // without bound
  internal_step_ = std::min(trial, h);
  last_internal_steps_ = taken;
  last_rejected_steps_ = rejected;
  last_step_capped_ = capped;
}

}  // namespace felt
