#include "core/imex_integrator.hpp"

#include <algorithm>

#include "core/check.hpp"

namespace felt {

bool ImexIntegrator::factorization_matches(std::span<const Real> inv_mass, Real h) const {
  return factored_ && h == factored_h_ && std::ranges::equal(inv_mass, factored_inv_mass_) &&
         pairs_ == factored_pairs_;
}

void ImexIntegrator::factorize(std::span<const Real> inv_mass, Real h) {
  const auto n = static_cast<Eigen::Index>(inv_mass.size());
  // A = M − h² H − h D with H_ij = k_ij, H_ii = −Σ_j k_ij (D likewise from c): a weighted graph
  // Laplacian plus the masses, so SPD. Pins are eliminated (identity row and column, Δv = 0).
  triplets_.clear();
  for (Eigen::Index p = 0; p < n; ++p) {
    triplets_.emplace_back(p, p, inv_mass[p] == 0 ? Real{1} : 1 / inv_mass[p]);
  }
  for (const LinearPair& pair : pairs_) {
    FELT_CHECK(pair.i < inv_mass.size() && pair.j < inv_mass.size() && pair.k >= 0 && pair.c >= 0);
    const Real w = h * h * pair.k + h * pair.c;
    const bool free_i = inv_mass[pair.i] != 0, free_j = inv_mass[pair.j] != 0;
    if (free_i) triplets_.emplace_back(pair.i, pair.i, w);
    if (free_j) triplets_.emplace_back(pair.j, pair.j, w);
    if (free_i && free_j) {
      triplets_.emplace_back(pair.i, pair.j, -w);
      triplets_.emplace_back(pair.j, pair.i, -w);
    }
  }
  matrix_.resize(n, n);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  ldlt_.compute(matrix_);
  FELT_CHECK(ldlt_.info() == Eigen::Success);
  ++factorizations_;

  factored_pairs_ = pairs_;
  factored_inv_mass_.assign(inv_mass.begin(), inv_mass.end());
  factored_h_ = h;
  factored_ = true;
}

void ImexIntegrator::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const std::size_t n = state.size();
  const auto inv_mass = system.inv_mass();
  force_.resize(n);
  rhs_.resize(static_cast<Eigen::Index>(n), 3);
  permuted_.resize(static_cast<Eigen::Index>(n), 3);
  dv_.resize(static_cast<Eigen::Index>(n), 3);

  // without linear forces A = M and the scheme is symplectic Euler
  if (!system.linear_force_pairs(pairs_)) pairs_.clear();
  // O(n + pairs) per step, like a force evaluation; refactorizing is far dearer
  if (!factorization_matches(inv_mass, h)) factorize(inv_mass, h);

  // Eq. 4.25 minus A v(t), with f_a = f − H x − D v: A Δv = h (f + h H v). The same solution,
  // but f_a and h H x, each of size k_s |l|, no longer cancel in the right-hand side.
  system.compute_forces(state.x, state.v, t, force_);
  for (std::size_t p = 0; p < n; ++p) rhs_.row(p) = (h * force_[p]).transpose();
  for (const LinearPair& pair : pairs_) {
    const Vec3 hv = (h * h * pair.k) * (state.v[pair.j] - state.v[pair.i]);  // h² (H v)_i
    rhs_.row(pair.i) += hv.transpose();
    rhs_.row(pair.j) -= hv.transpose();
  }
  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) rhs_.row(p).setZero();
  }

  // Δv = P⁻¹ L⁻ᵀ D⁻¹ L⁻¹ P rhs, spelled out: Eigen's solve() permutes back in place, which
  // allocates a mask every call
  permuted_.noalias() = ldlt_.permutationP() * rhs_;
  ldlt_.matrixL().solveInPlace(permuted_);
  permuted_.array().colwise() /= ldlt_.vectorD().array();
  ldlt_.matrixU().solveInPlace(permuted_);
  dv_.noalias() = ldlt_.permutationPinv() * permuted_;

  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) continue;
    state.v[p] += dv_.row(p).transpose();
    state.x[p] += h * state.v[p];
  }
}

}  // namespace felt
