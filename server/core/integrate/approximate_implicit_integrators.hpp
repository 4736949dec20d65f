#pragma once
// Two approximations of backward Euler for cloth that replace ∂f/∂x by the constant Laplacian H
// of the system's linear pairs (the structural springs' −k l; thesis 1 §4.3) and ignore ∂f/∂v:
//   (M − h² H) Δv = b,   b = h (f + h H v),   v += Δv,   x += h v          (thesis eq. 4.17)
// with f the full force, so the pairs' −k l is implicit and the rest (k r l̂, the springs'
// damping, shear, bend, gravity, drag, wind) explicit. Desbrun et al. solve it exactly and
// correct the angular momentum the constant H loses; Kang et al. solve it approximately in
// linear time. Both are first order and damp oscillations; without linear pairs both are
// symplectic Euler.

#include <cstdint>
#include <span>
#include <vector>

#include "core/integrate/integrator.hpp"
#include "core/integrate/linear_pair_step.hpp"

namespace felt {

/// Desbrun, Schröder & Barr 1999 (with Meyer et al. 2001's pseudo-code, thesis 1 §4.4.2).
///
/// The filter (M − h² H)⁻¹ is a sparse LDLᵀ factorization made once and again only when h, the
/// masses or pins, or the pairs change — the paper's dense W = (I − h²/m H)⁻¹ for any masses,
/// at O(n) per step instead of O(n²). It differs from `imex` in two ways: the pairs' damping
/// stays explicit (the paper drops ∂f/∂v; `imex` takes it implicitly, isotropic), and the
/// angular momentum correction below. External forces (gravity, wind, user forces) go through
/// the filter with the rest instead of being added after it as in the pseudo-code; a uniform
/// field passes it unchanged (H 1 = 0). The paper's closing inverse dynamics is the body's own
/// stretch limiting option.
///
/// The correction. H treats a spring's turning as stretching, so the filter damps rotation:
/// the filtered impulses m_i Δv_i exert an angular impulse about the centre of mass x_G that
/// the forces did not, τ = Σ r_i × (m_i Δv_i − h f_i), r_i = x_i − x_G. The paper cancels it
/// with a force h (x_G − x_i) ∧ δT on each particle, δT = Σ (x_G − x_i) ∧ F_i^filtered (its
/// pseudo-code's Σ F_i ∧ x_i; the "more direct" Σ x_i ∧ F_i printed beside it has the wrong
/// sign), added to the positions only and scaled by h, not by the inertia. Here the correction
/// is the rigid rotation whose angular impulse is exactly −τ: Δv_i += ω × r_i with I ω = −τ,
/// I = Σ m_i (|r_i|² 𝟙 − r_i r_iᵀ) the inertia tensor about x_G (pseudo-inverted: a collinear
/// body has no inertia about its line, and no τ along it either). It changes neither the
/// momentum nor, to first order, any spring's length, and with x += h v(t+h) it makes the step
/// keep L = Σ m x × v exactly, up to the torque of the forces themselves (gravity, wind, drag
/// and user forces keep theirs). It applies only to bodies without pins: a pin's reaction
/// torque is physical and not separable from the filter's, and a pinned body's angular momentum
/// is not conserved anyway.
class DesbrunIntegrator final : public Integrator {
 public:
  /// `correct_angular_momentum` false leaves the correction out (for comparison only).
  explicit DesbrunIntegrator(bool correct_angular_momentum = true)
      : correct_angular_momentum_(correct_angular_momentum) {}

  std::string_view name() const override { return "desbrun"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;

  /// How many times the filter was factorized so far.
  std::int64_t factorizations() const { return linear_step_.factorizations(); }

 private:
  void restore_angular_momentum(std::span<const Real> inv_mass, std::span<const Vec3> x, Real h);

  bool correct_angular_momentum_;
  LinearPairStep linear_step_{false};
  LinearPairStep::Columns dv_;
};

/// Kang, Choi, Cho & Lee 2000/2001 (thesis 1 §4.4.2): the same equation without a global solve.
/// Row i of (M − h² H) Δv = b is (m_i + h² K_i) Δv_i − h² Σ_j k_ij Δv_j = b_i, K_i = Σ_j k_ij
/// over i's pairs. Kang et al. approximate the neighbours' Δv_j by dropping their own
/// neighbours, Δv⁰_j = b_j / (m_j + h² K_j), and get
///   Δv_i = (b_i + h² Σ_j k_ij Δv⁰_j) / (m_i + h² K_i),   b = h (f + h H v),
/// which is the paper's [h f̃_i + k h² Σ_j h f̃_j / (m_j + k h² n_j)] / (m_i + k h² n_i) with
/// each pair's own k and each particle's own mass; pinned particles have Δv = 0 (as neighbours
/// too). That is two Jacobi iterations from Δv = 0, O(n + pairs) per step with nothing to
/// factorize, so h, masses and stiffness may change freely. Not more: a truncated Jacobi series
/// P ≈ (M − h² H)⁻¹ steps a mode of −H's eigenvalue λ stably only while q = p h² λ ≤ 4/3. On a
/// uniform grid two terms keep q ≤ 1 at any h, while an odd number of terms lets the
/// alternating (checkerboard) mode reach q → 2 as h² k/m grows, and explode.
/// The price: a connected body's momentum is not kept, and smooth forces get through only in
/// part. From rest a falling cloth's particle gains h g (1 − ε²), ε = h² K/(m + h² K) (uniform
/// neighbours): right to first order, but where h² K ≫ m the cloth hardly falls. Kang et al.'s
/// wrinkle splines and bucket-sorted stretch limiting are not part of it (stretch limiting is
/// the body's own option).
class KangIntegrator final : public Integrator {
 public:
  std::string_view name() const override { return "kang"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;

 private:
  LinearPairStep linear_step_{false};
  std::vector<Real> diagonal_;  ///< m_i + h² K_i
  LinearPairStep::Columns guess_, dv_;
};

}  // namespace felt
