#pragma once
// Backward Euler for cloth, linearized once per step (Baraff & Witkin 1998; thesis 1 §4.3):
//   (M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h (∂f/∂x) v₀),   x₁ = x₀ + h (v₀ + Δv)   (4.14)
// solved by the filtered PCG so pins hold exactly, started from the last step's Δv. Unconditionally
// stable on a linear oscillator, first order, and it damps energy.

#include <algorithm>

#include "core/integrate/filtered_conjugate_gradient.hpp"
#include "core/integrate/implicit_system_matrix.hpp"
#include "core/integrate/integrator.hpp"

namespace felt {

class ImplicitEuler final : public Integrator {
 public:
  std::string_view name() const override { return "implicit_euler"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  /// Forgets the last Δv: the next solve starts from zero.
  void reset() override { last_h_ = 0; }

  /// The linear solve of the last step.
  const FilteredConjugateGradient::Result& last_solve() const { return last_solve_; }
  FilteredConjugateGradient& solver() { return solver_; }
  /// Each conjugate-gradient iteration counts in the step budget as an internal step (a pass
  /// over the springs, as an explicit step is): a solve takes at most `cap` of them, and never
  /// more than kMaxIterations.
  void limit_internal_steps(int cap) override {
    solver_.max_iterations = std::clamp(cap, 1, kMaxIterations);
  }
  int last_internal_steps() const override { return std::max(1, last_solve_.iterations); }
  /// The last solve stopped at the solver's max_iterations unconverged.
  bool last_step_capped() const override {
    return !last_solve_.converged && last_solve_.iterations >= solver_.max_iterations;
  }
  static constexpr int kMaxIterations = 1000;

 private:
  ForceJacobian jacobian_;
  ImplicitSystemMatrix matrix_;
  FilteredConjugateGradient solver_;
  FilteredConjugateGradient::Result last_solve_;
  std::vector<Vec3> force_, rhs_, dv_, dfdx_, dfdv_, inv_diagonal_;
  std::vector<Mat3> filter_;
  Real last_h_ = 0;  ///< of the step dv_ is from; 0: none to start from
};

}  // namespace felt
