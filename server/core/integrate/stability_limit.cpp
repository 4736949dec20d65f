#include "core/integrate/stability_limit.hpp"

#include <array>
#include <cmath>
#include <complex>

namespace felt {
namespace {

using Complex = std::complex<Real>;

/// |R(z)|² > 1, judged as 2 Re w + |w|² with w = R(z) − 1 (summed without the 1, whose rounding
/// would hide growth of order (ωh)⁴ at small steps) and beyond its own rounding error.
bool grows(std::span<const Real> coefficients, Complex z) {
  Complex w = 0;
  for (std::size_t k = coefficients.size(); k-- > 1;) w = (w + coefficients[k]) * z;
  const Real growth = 2 * w.real() + std::norm(w);
  return growth >
         8 * std::numeric_limits<Real>::epsilon() * (2 * std::abs(w.real()) + std::norm(w));
}

// Steps sampled before the bisection, spaced quadratically up to kSpan/|λ| so that the shortest
// is 1e-6 of it: a mode that short steps already grow is told from a stable one.
constexpr int kSamples = 1000;
constexpr Real kSpan = 8;  // beyond every explicit scheme's stability interval (RK4's 2.83)
constexpr int kBisections = 60;

}  // namespace

Real verlet_step_limit(const OscillatorMode& mode) {
  // (−c + √(c² + 4ω²)) / ω², written without the cancellation and the 0/0 at ω = 0
  return 4 / (mode.rate + std::sqrt(mode.rate * mode.rate + 4 * mode.omega_squared));
}

Real second_order_verlet_step_limit(const OscillatorMode& mode) {
  // (−2c + √(4c² + 4ω²)) / ω², without the cancellation
  return 2 / (mode.rate + std::sqrt(mode.rate * mode.rate + mode.omega_squared));
}

Real polynomial_step_limit(std::span<const Real> coefficients, const OscillatorMode& mode) {
  const Real c = mode.rate, w2 = mode.omega_squared;
  // the roots of λ² + cλ + ω² = 0; a complex pair has one |R| for both (R has real coefficients)
  const Real discriminant = c * c - 4 * w2;
  std::array<Complex, 2> roots;
  if (discriminant < 0) {
    roots = {Complex(-c / 2, std::sqrt(-discriminant) / 2), Complex(-c / 2, 0)};
    roots[1] = roots[0];
  } else {
    // −c/2 − √ first, then ω²/that (Vieta), which does not cancel for ω ≪ c
    const Real larger = -(c + std::sqrt(discriminant)) / 2;
    roots = {Complex(larger, 0), Complex(larger == 0 ? 0 : w2 / larger, 0)};
  }
  const Real fastest = std::abs(roots[0]);
  if (fastest == 0) return kNoStepLimit;
  const auto unstable = [&](Real h) {
    return grows(coefficients, h * roots[0]) || grows(coefficients, h * roots[1]);
  };
  Real stable = 0;
  for (int k = 1; k <= kSamples; ++k) {
    const Real fraction = static_cast<Real>(k) / kSamples;
    const Real h = kSpan / fastest * fraction * fraction;
    if (!unstable(h)) {
      stable = h;
      continue;
    }
    if (stable == 0) return 0;
    Real high = h;
    for (int i = 0; i < kBisections; ++i) {
      const Real middle = (stable + high) / 2;
      (unstable(middle) ? high : stable) = middle;
    }
    return stable;
  }
  return stable;
}

}  // namespace felt
