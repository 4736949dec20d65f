#include "core/cloth/spring_constraint_solve.hpp"

namespace felt {

bool SpringConstraintSolve::factorize(const ClothModel& model, std::span<const Real> inv_mass,
                                      std::span<const std::uint32_t> springs,
                                      std::span<const Vec3> x) {
  const std::size_t n = model.particle_count();
  const std::size_t m = springs.size();
  springs_.assign(springs.begin(), springs.end());
  directions_.resize(m);
  first_.assign(n + 1, 0);
  for (std::size_t k = 0; k < m; ++k) {
    const Spring& s = model.springs[springs_[k]];
    const Vec3 d = x[s.j] - x[s.i];
    const Real length = d.norm();
    directions_[k] = length > 0 ? Vec3(d / length) : Vec3::Zero();
    ++first_[s.i + 1];
    ++first_[s.j + 1];
  }
  for (std::size_t p = 0; p < n; ++p) first_[p + 1] += first_[p];
  incident_.resize(first_[n]);
  std::vector<std::uint32_t> fill(first_.begin(), first_.end() - 1);
  for (std::size_t k = 0; k < m; ++k) {
    const Spring& s = model.springs[springs_[k]];
    incident_[fill[s.i]++] = static_cast<std::uint32_t>(2 * k);
    incident_[fill[s.j]++] = static_cast<std::uint32_t>(2 * k + 1);
  }

  // (J W Jᵀ)_kl = Σ over the particles p that springs k and l share of w_p (±n_k)·(±n_l), the
  // sign + at a spring's end j, − at its end i; the lower triangle is all LDLᵀ reads. Pinned
  // particles (w = 0) add explicit zeros, so that the pattern depends on the springs alone.
  triplets_.clear();
  for (std::size_t k = 0; k < m; ++k) {
    const Spring& s = model.springs[springs_[k]];
    const auto row = static_cast<Eigen::Index>(k);
    triplets_.emplace_back(row, row, (1 + kRegularization) * (inv_mass[s.i] + inv_mass[s.j]));
  }
  for (std::size_t p = 0; p < n; ++p) {
    const Real w = inv_mass[p];
    for (std::uint32_t a = first_[p]; a < first_[p + 1]; ++a) {
      for (std::uint32_t b = first_[p]; b < a; ++b) {
        const std::uint32_t ka = incident_[a] / 2, kb = incident_[b] / 2;
        const Real sign = (incident_[a] % 2 == incident_[b] % 2) ? 1 : -1;
        const Real value = sign * w * directions_[ka].dot(directions_[kb]);
        triplets_.emplace_back(std::max(ka, kb), std::min(ka, kb), value);
      }
    }
  }
  const auto size = static_cast<Eigen::Index>(m);
  matrix_.resize(size, size);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  if (!ldlt_) ldlt_ = std::make_unique<Eigen::SimplicialLDLT<SparseMatrix>>();
  if (!analyzed_ || analyzed_springs_ != springs_) {
    ldlt_->analyzePattern(matrix_);
    analyzed_springs_ = springs_;
    analyzed_ = true;
  }
  ldlt_->factorize(matrix_);
  return ldlt_->info() == Eigen::Success;
}

void SpringConstraintSolve::correct(const ClothModel& model, std::span<const Real> inv_mass,
                                    const Eigen::VectorXd& r, std::span<Vec3> y) {
  mu_ = ldlt_->solve(r);
  for (std::size_t k = 0; k < springs_.size(); ++k) {
    const Spring& s = model.springs[springs_[k]];
    const Vec3 impulse = mu_[static_cast<Eigen::Index>(k)] * directions_[k];
    y[s.i] += inv_mass[s.i] * impulse;
    y[s.j] -= inv_mass[s.j] * impulse;
  }
}

}  // namespace felt
