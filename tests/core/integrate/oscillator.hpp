#pragma once
// The spring–mass oscillator the integrator tests measure against: a DynamicSystem with an
// analytic solution, and the convergence-order measurement built on it.

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "core/integrate/integrator.hpp"

namespace felt::test {

/// Particles each on its own spring to the origin: f = −k x − c v + push. Particles do not
/// interact; an inverse mass of 0 pins one. Counts its force evaluations.
class Oscillator final : public DynamicSystem {
 public:
  /// One particle of mass `mass`.
  Oscillator(Real mass, Real stiffness, Vec3 push = Vec3::Zero(), Real damping = 0)
      : Oscillator(std::vector<Real>{1 / mass}, stiffness, push, damping) {}
  /// As many particles as inverse masses. (Spell one particle std::vector<Real>{m⁻¹}: a braced
  /// single value would pick the constructor above.)
  Oscillator(std::vector<Real> inv_mass, Real stiffness, Vec3 push = Vec3::Zero(), Real damping = 0)
      : inv_mass_(std::move(inv_mass)), stiffness_(stiffness), push_(push), damping_(damping) {}

  std::span<const Real> inv_mass() const override { return inv_mass_; }
  void compute_forces(std::span<const Vec3> x, std::span<const Vec3> v, Real,
                      std::span<Vec3> f) const override {
    ++evaluations_;
    for (std::size_t p = 0; p < x.size(); ++p) f[p] = -stiffness_ * x[p] - damping_ * v[p] + push_;
  }

  /// ½ m v² + ½ k x² of the first particle.
  Real energy(const ParticleState& s) const {
    return 0.5 / inv_mass_[0] * s.v[0].squaredNorm() + 0.5 * stiffness_ * s.x[0].squaredNorm();
  }
  int evaluations() const { return evaluations_; }
  /// Pins (0) or unpins particle p, as ClothBody::pin and unpin do.
  void set_inv_mass(std::size_t p, Real inv_mass) { inv_mass_[p] = inv_mass; }

 private:
  std::vector<Real> inv_mass_;
  Real stiffness_;
  Vec3 push_;
  Real damping_;
  mutable int evaluations_ = 0;
};

inline ParticleState start_at(const Vec3& x, const Vec3& v = Vec3::Zero()) {
  return {{x}, {v}};
}

// ω = 2π rad/s: one period per second
constexpr Real kMass = 1;
const Real kOmega = 2 * M_PI;
const Real kStiffness = kOmega * kOmega * kMass;

/// The oscillator m ẍ + c ẋ + k x = 0 from x(0) = 1, v(0) = 0, underdamped (ζ = c/(2mω) < 1):
///   x = e^(−ζωt) (cos ω_d t + ζω/ω_d sin ω_d t),  v = −(ω²/ω_d) e^(−ζωt) sin ω_d t,
/// ω_d = ω √(1 − ζ²).
struct Exact {
  Real x;
  Real v;
};
inline Exact exact_oscillator(Real t, Real zeta = 0) {
  const Real omega_d = kOmega * std::sqrt(1 - zeta * zeta);
  const Real decay = std::exp(-zeta * kOmega * t);
  return {decay * (std::cos(omega_d * t) + zeta * kOmega / omega_d * std::sin(omega_d * t)),
          -kOmega * kOmega / omega_d * decay * std::sin(omega_d * t)};
}

/// Largest error of the state (x, v/ω) against the exact solution over one period, with steps
/// of h (or, with `uneven`, alternating steps of ⅔h and 4⁄3h, which average to h).
/// (The error at exactly one period is no measure: some schemes are superconvergent there.)
inline Real oscillator_error(Integrator& integrator, Real h, Real zeta = 0, bool uneven = false) {
  integrator.reset();
  Oscillator system(kMass, kStiffness, Vec3::Zero(), 2 * zeta * kMass * kOmega);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const long steps = std::lround(1.0 / h);
  Real worst = 0;
  Real t = 0;
  for (long n = 0; n < steps; ++n) {
    const Real dt = uneven ? (n % 2 == 0 ? 2 * h / 3 : 4 * h / 3) : h;
    integrator.step(system, state, t, dt);
    t = uneven && n % 2 == 0 ? (n + 1) * h - h / 3 : (n + 1) * h;
    const Exact exact = exact_oscillator(t, zeta);
    worst =
        std::max(worst, std::hypot(state.x[0].x() - exact.x, (state.v[0].x() - exact.v) / kOmega));
  }
  return worst;
}

/// The convergence order measured from the errors at h, h/2 and h/4: the mean of
/// log2(e(h)/e(h/2)) and log2(e(h/2)/e(h/4)).
inline Real measured_order(Integrator& integrator, Real h, Real zeta = 0, bool uneven = false) {
  const Real e1 = oscillator_error(integrator, h, zeta, uneven);
  const Real e2 = oscillator_error(integrator, h / 2, zeta, uneven);
  const Real e4 = oscillator_error(integrator, h / 4, zeta, uneven);
  return 0.5 * (std::log2(e1 / e2) + std::log2(e2 / e4));
}

}  // namespace felt::test
