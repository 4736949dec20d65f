#pragma once
// Projective dynamics for mass-spring systems (Liu, Bargteil, O'Brien & Kavan, "Fast Simulation
// of Mass-Spring Systems", SIGGRAPH Asia 2013; Bouaziz et al., "Projective Dynamics", 2014).
// Backward Euler's step is the minimum over x of
//   ½ ‖x − x_n − h v_n − h² M⁻¹ f‖²_M + h² Σ_s ½ k_s ‖(x_i − x_j) − d_s‖²,   |d_s| = r_s
// (f every force but the springs', at the start of the step). Alternating its two halves is
// block coordinate descent, so every iteration lowers it:
//   local:  d_s = r_s l̂_s, the rest-length vector nearest each spring of the current iterate;
//   global: (M + h D + h² L) Δv = h (f + Σ_s [k_s (d_s − l_s) − c_s (v_ij · l̂_s) l̂_s] + h H v),
// the constant sparse system of LinearPairStep with every spring a pair (L = −H the Laplacian of
// the k_s, D that of the damping c_s, taken isotropic as IMEX takes it), factorized once; l_s and
// v_ij are the spring and its ends' relative velocity at the start of the step, x = x_n +
// h (v_n + Δv) the next iterate. The first iteration starts from x_n, where d_s − l_s is the
// spring's stretch: it is the IMEX step (Eberhardt et al. 2000) with every spring implicit, and
// the iterations go on from it towards backward Euler. Unconditionally stable, first order,
// damped like backward Euler; the cost is a force evaluation and two triangular solves per
// iteration, whatever the stiffness. Optionally accelerated by the Chebyshev semi-iterative
// method (Wang, "A Chebyshev Semi-Iterative Approach for Accelerating Projective and
// Position-based Dynamics", SIGGRAPH Asia 2015), given an estimate ρ of the iterations' rate.

#include <algorithm>
#include <vector>

#include "core/integrate/distance_constraint.hpp"
#include "core/integrate/integrator.hpp"
#include "core/integrate/linear_pair_step.hpp"

namespace felt {

class ProjectiveDynamics final : public Integrator {
 public:
  static constexpr int kDefaultIterations = 10;
  static constexpr int kMaxIterations = 100;
  static constexpr Real kMaxChebyshevRho = 0.9999;

  /// Takes `iterations` (1 to kMaxIterations) local/global iterations per step, accelerated
  /// when `chebyshev_rho` (the iterations' estimated spectral radius, below 1) is not 0.
  explicit ProjectiveDynamics(int iterations = kDefaultIterations, Real chebyshev_rho = 0);

  std::string_view name() const override { return "projective_dynamics"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;

  int iterations() const { return iterations_; }
  Real chebyshev_rho() const { return chebyshev_rho_; }

  /// Each local/global iteration counts in the step budget as an internal step: a step takes
  /// at most `cap` of them, and never more than its `iterations`.
  void limit_internal_steps(int cap) override { cap_ = std::max(1, cap); }
  int last_internal_steps() const override { return last_iterations_; }
  bool last_step_capped() const override { return last_iterations_ < iterations_; }

 private:
  // Wang 2015's delay S before the acceleration starts (few: a served step affords few
  // iterations) and its under-relaxation γ
  static constexpr int kChebyshevDelay = 2;
  static constexpr Real kUnderRelaxation = 0.9;

  /// ω of iteration k (from 0) given the last one's.
  Real chebyshev_weight(int k, Real omega) const;
  /// force_ = the other forces plus every spring's pull towards its projection at `iterate`.
  void project(const ParticleState& start, const std::vector<Vec3>& iterate);

  int iterations_;
  Real chebyshev_rho_;
  int cap_ = kMaxIterations;
  int last_iterations_ = 0;
  ConstraintClasses springs_;
  std::vector<LinearPair> pairs_;
  std::vector<Vec3> others_, force_, iterate_, previous_;
  LinearPairStep linear_step_{true};
  LinearPairStep::Columns dv_;
};

}  // namespace felt
