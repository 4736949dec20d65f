#pragma once
// Preconditioned conjugate gradient with per-particle constraint filters: the "modified PCG"
// of Baraff & Witkin 1998 §5.3. A filter S_p projects particle p's unknowns onto the directions
// it may move in (0 for a pin, I − n nᵀ for a particle held in a plane, I for a free one), so
// constraints are enforced exactly inside the solve instead of by penalty.

#include <functional>
#include <span>
#include <vector>

#include "core/math/types.hpp"

namespace felt {

class FilteredConjugateGradient {
 public:
  /// y = A x for the symmetric positive (semi)definite operator being inverted.
  using Operator = std::function<void(std::span<const Vec3> x, std::span<Vec3> y)>;

  struct Result {
    int iterations = 0;
    bool converged = false;
    Real residual_ratio = 0;  ///< |r|_P / |b|_P at the end
  };

  Real tolerance = 1e-8;  ///< on the preconditioned residual relative to the right-hand side
  int max_iterations = 1000;

  /// Solves S A x = S b, starting from (and returning in) x, whose filtered-out components must
  /// already hold the constrained values. `inv_diagonal` is a Jacobi preconditioner per
  /// component; `filter` the S_p per particle.
  Result solve(const Operator& apply, std::span<const Vec3> b, std::span<const Vec3> inv_diagonal,
               std::span<const Mat3> filter, std::span<Vec3> x);

 private:
  std::vector<Vec3> r_, c_, q_, s_;
};

}  // namespace felt
