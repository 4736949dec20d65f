#pragma once
// How stiff a body is at one of its points, from its own stiffness matrix (issue 26: the local
// model's surface stiffness, which a fit to the pushes gets far too low where the whole body
// swings away). In linear statics a load b on the free nodes moves them u = K⁻¹ b, K = −∂f/∂x;
// a unit load along n spread over nodes with weights w_i (a point inside a triangle, b_i = w_i n)
// moves its own point by c = bᵀ K⁻¹ b along n: the point's compliance, the diagonal entry of the
// flexibility matrix K⁻¹ along n (Maxwell's reciprocal theorem makes it the same whichever way it
// is read). k = 1/c is the stiffness the body has at that point when everything else is left
// free to settle: K condensed onto that one degree of freedom (static condensation, Guyan 1965,
// "Reduction of stiffness and mass matrices", AIAA J. 3(2)).
//
// Over a horizon τ instead of at rest: a force held from rest for τ moves a free mass m by
// F τ² / 2m, as a spring of 2m/τ² would, and a spring by F/k; K + 2M/τ² gives each alone
// exactly, and for a body the give a push causes before the body has had τ to settle. How far
// that is above the static stiffness says whether the point answers a push of that length as a
// spring (static) or by its inertia (a light cloth that swings away).

#include <memory>
#include <span>
#include <vector>

#include <Eigen/SparseCore>

#include "core/math/types.hpp"

namespace felt {

/// A node of a point load and its share of it.
struct WeightedNode {
  std::uint32_t node = 0;
  Real weight = 1;
};

/// What PointCompliance::factor needs of a body, copied out of it: its stiffness matrix K
/// (3n × 3n), the nodes held and each node's mass; another thread can factor it while the body
/// steps on.
struct ComplianceProblem {
  Eigen::SparseMatrix<Real> stiffness;
  std::vector<bool> held;
  std::vector<Real> mass;
};

class PointCompliance {
 public:
  /// Unknown: every stiffness() is 0.
  PointCompliance() = default;

  /// K (3n × 3n, symmetric, of n nodes), plus 2M/τ² for a horizon τ > 0 with `mass` per node,
  /// factored once (sparse LDLᵀ), with the nodes `held[p]` fixed (pins, supports: their rows and
  /// columns left out); unknown when the matrix is not positive definite on the free nodes (a
  /// free body, or a slack cloth, at rest can move without any force resisting).
  static PointCompliance factor(const Eigen::SparseMatrix<Real>& stiffness, std::vector<bool> held,
                                std::span<const Real> mass = {}, Real horizon = 0);
  /// The same, of `problem`.
  static PointCompliance factor(const ComplianceProblem& problem, Real horizon = 0) {
    return factor(problem.stiffness, problem.held, problem.mass, horizon);
  }

  /// N/m along unit `direction` of a load spread over `load` (weights summing to 1): 1/(bᵀ K⁻¹ b);
  /// 0 while unknown, for a load on no free node, or on a node out of range.
  Real stiffness(std::span<const WeightedNode> load, const Vec3& direction) const;

  bool known() const { return factor_ != nullptr; }
  std::size_t node_count() const { return held_.size(); }

 private:
  struct Factor;
  std::shared_ptr<const Factor> factor_;
  std::vector<bool> held_;
};

}  // namespace felt
