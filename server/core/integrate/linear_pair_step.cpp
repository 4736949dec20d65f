#include "core/integrate/linear_pair_step.hpp"

#include <algorithm>

#include "core/math/check.hpp"

namespace felt {

void LinearPairStep::assemble(const DynamicSystem& system, const ParticleState& state, Real t,
                              Real h) {
  // without linear forces H = 0 and b = h f
  if (!system.linear_force_pairs(pairs_)) pairs_.clear();
  force_.resize(state.size());
  system.compute_forces(state.x, state.v, t, force_);
  assemble_rhs(system.inv_mass(), state, h);
}

void LinearPairStep::set_pairs(std::span<const LinearPair> pairs) {
  pairs_.assign(pairs.begin(), pairs.end());
}

void LinearPairStep::assemble(std::span<const Real> inv_mass, const ParticleState& state, Real h,
                              std::span<const Vec3> force) {
  FELT_CHECK(force.size() == state.size());
  force_.assign(force.begin(), force.end());
  assemble_rhs(inv_mass, state, h);
}

void LinearPairStep::assemble_rhs(std::span<const Real> inv_mass, const ParticleState& state,
                                  Real h) {
  const std::size_t n = state.size();
  rhs_.resize(static_cast<Eigen::Index>(n), 3);
  for (std::size_t p = 0; p < n; ++p) rhs_.row(p) = (h * force_[p]).transpose();
  for (const LinearPair& pair : pairs_) {
    const Vec3 hv = (h * h * pair.k) * (state.v[pair.j] - state.v[pair.i]);  // h² (H v)_i
    rhs_.row(pair.i) += hv.transpose();
    rhs_.row(pair.j) -= hv.transpose();
  }
  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) rhs_.row(p).setZero();
  }
}

bool LinearPairStep::factorization_matches(std::span<const Real> inv_mass, Real h) const {
  return factored_ && h == factored_h_ && std::ranges::equal(inv_mass, factored_inv_mass_) &&
         pairs_ == factored_pairs_;
}

void LinearPairStep::factorize(std::span<const Real> inv_mass, Real h) {
  const auto n = static_cast<Eigen::Index>(inv_mass.size());
  // A = M − h² H − θ h D: a weighted graph Laplacian plus the masses, so SPD. Pins are
  // eliminated (identity row and column, Δv = 0).
  triplets_.clear();
  for (Eigen::Index p = 0; p < n; ++p) {
    triplets_.emplace_back(p, p, inv_mass[p] == 0 ? Real{1} : 1 / inv_mass[p]);
  }
  for (const LinearPair& pair : pairs_) {
    FELT_CHECK(pair.i < inv_mass.size() && pair.j < inv_mass.size() && pair.k >= 0 && pair.c >= 0);
    const Real w = h * h * pair.k + (implicit_damping_ ? h * pair.c : 0);
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

void LinearPairStep::solve(std::span<const Real> inv_mass, Real h, Columns& dv) {
  FELT_CHECK(inv_mass.size() == static_cast<std::size_t>(rhs_.rows()));
  // O(n + pairs) per step, like a force evaluation; refactorizing is far dearer
  if (!factorization_matches(inv_mass, h)) factorize(inv_mass, h);

  // Δv = P⁻¹ L⁻ᵀ D⁻¹ L⁻¹ P b, spelled out: Eigen's solve() permutes back in place, which
  // allocates a mask every call
  permuted_.resize(rhs_.rows(), 3);
  permuted_.noalias() = ldlt_.permutationP() * rhs_;
  ldlt_.matrixL().solveInPlace(permuted_);
  permuted_.array().colwise() /= ldlt_.vectorD().array();
  ldlt_.matrixU().solveInPlace(permuted_);
  dv.resize(rhs_.rows(), 3);
  dv.noalias() = ldlt_.permutationPinv() * permuted_;
}

void apply_velocity_change(std::span<const Real> inv_mass, Real h,
                           const LinearPairStep::Columns& dv, ParticleState& state) {
  for (std::size_t p = 0; p < state.size(); ++p) {
    if (inv_mass[p] == 0) continue;
    state.v[p] += dv.row(static_cast<Eigen::Index>(p)).transpose();
    state.x[p] += h * state.v[p];
  }
}

}  // namespace felt
