#pragma once
// IMEX Euler of Eberhardt et al. 2000 in Melis's corrected form (thesis 1 §4.4, eq. 4.25). The
// system's constant linear forces f_g = H x + D v (the structural springs' −k_s l and their
// damping) are implicit, the rest f_a = f − f_g (their rest-length part k_s r l̂, shear, bend,
// gravity, drag) explicit:
//   (M − h² H − h D) v(t+h) = M v(t) + h f_a(x(t), v(t)) + h H x(t),   x(t+h) = x(t) + h v(t+h)
// H and D are constant, so the matrix is factorized once and only again when h, the masses or
// pins, or the spring constants change. First order; on a linear spring it is backward Euler.

#include <cstdint>

#include "core/integrate/integrator.hpp"
#include "core/integrate/linear_pair_step.hpp"

namespace felt {

class ImexIntegrator final : public Integrator {
 public:
  std::string_view name() const override { return "imex"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;

  /// How many times the matrix was factorized so far.
  std::int64_t factorizations() const { return linear_step_.factorizations(); }

 private:
  // Eq. 4.25 minus A v(t), with f_a = f − H x − D v, is LinearPairStep's A Δv = h (f + h H v):
  // the same solution, but f_a and h H x, each of size k_s |l|, no longer cancel in b
  LinearPairStep linear_step_{true};
  LinearPairStep::Columns dv_;
};

}  // namespace felt
