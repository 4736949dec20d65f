#pragma once
// The largest eigenvalue of a symmetric positive semidefinite sparse matrix by Lanczos
// iteration, for the explicit step limit of the soft solids (thesis 2 §4.5): 2/√λ_max(M⁻¹K) is
// where position Verlet turns unstable, and a per-row bound (Gershgorin) put the step at 0.3–0.55
// of that limit, which cost as many extra substeps.

#include <cstdint>
#include <vector>

#include <Eigen/SparseCore>

#include "core/math/types.hpp"

namespace felt {

/// Adds the 3×3 block `block` at block row `a`, block column `b` (nodes) to `triplets`.
void add_block(std::vector<Eigen::Triplet<Real>>& triplets, std::uint32_t a, std::uint32_t b,
               const Mat3& block);

/// The 3n × 3n matrix of `node_count` nodes with the blocks of `triplets` (repeats add up).
Eigen::SparseMatrix<Real> block_matrix(std::size_t node_count,
                                       const std::vector<Eigen::Triplet<Real>>& triplets);

/// λ_max of the symmetric positive semidefinite `matrix`, from above to within
/// `relative_tolerance`: the largest Ritz value θ of a Lanczos run plus its residual bound
/// β|s_m| (Paige 1971: an eigenvalue lies within it of θ; a Ritz value approaches the largest
/// eigenvalue from below, and the start vector has every eigenvector in it, so that eigenvalue
/// is λ_max). Deterministic: the start vector is a fixed pseudo-random one. 0 for an empty or
/// zero matrix.
Real largest_eigenvalue(const Eigen::SparseMatrix<Real>& matrix, Real relative_tolerance = 1e-3);

}  // namespace felt
