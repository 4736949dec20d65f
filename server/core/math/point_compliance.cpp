#include "core/math/point_compliance.hpp"

#include <cmath>

#include <Eigen/SparseCholesky>

namespace felt {

struct PointCompliance::Factor {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<Real>> ldlt;
};

PointCompliance PointCompliance::factor(const Eigen::SparseMatrix<Real>& stiffness,
                                        std::vector<bool> held, std::span<const Real> mass,
                                        Real horizon) {
  const auto n = static_cast<Eigen::Index>(held.size());
  if (stiffness.rows() != 3 * n || stiffness.cols() != 3 * n || n == 0) return {};
  if (horizon > 0 && mass.size() != held.size()) return {};
  // a held node's rows and columns become the identity's: it decouples and moves by its load,
  // which stiffness() never puts on it
  Eigen::SparseMatrix<Real> k = stiffness;
  for (Eigen::Index col = 0; col < k.outerSize(); ++col) {
    for (Eigen::SparseMatrix<Real>::InnerIterator it(k, col); it; ++it) {
      if (held[static_cast<std::size_t>(it.row() / 3)] ||
          held[static_cast<std::size_t>(it.col() / 3)]) {
        it.valueRef() = it.row() == it.col() ? 1 : 0;
      }
    }
  }
  for (Eigen::Index p = 0; p < n; ++p) {
    const auto node = static_cast<std::size_t>(p);
    const Real inertia = horizon > 0 ? 2 * mass[node] / (horizon * horizon) : 0;
    for (int a = 0; a < 3; ++a) {
      if (held[node]) {
        k.coeffRef(3 * p + a, 3 * p + a) = 1;
      } else if (inertia > 0) {
        k.coeffRef(3 * p + a, 3 * p + a) += inertia;
      }
    }
  }
  auto factor = std::make_shared<Factor>();
  factor->ldlt.compute(k);
  if (factor->ldlt.info() != Eigen::Success) return {};
  // positive definite: every pivot positive, none lost to rounding against the largest (a
  // direction nothing resists factors as a pivot of rounding's size)
  const auto pivots = factor->ldlt.vectorD();
  if (!(pivots.minCoeff() > 1e-12 * pivots.cwiseAbs().maxCoeff())) return {};
  PointCompliance out;
  out.factor_ = std::move(factor);
  out.held_ = std::move(held);
  return out;
}

Real PointCompliance::stiffness(std::span<const WeightedNode> load, const Vec3& direction) const {
  if (!known()) return 0;
  const auto n = static_cast<Eigen::Index>(held_.size());
  Eigen::VectorX<Real> b = Eigen::VectorX<Real>::Zero(3 * n);
  bool loaded = false;
  for (const WeightedNode& w : load) {
    if (w.node >= held_.size()) return 0;
    if (held_[w.node]) continue;
    b.segment<3>(3 * static_cast<Eigen::Index>(w.node)) += w.weight * direction;
    loaded = loaded || w.weight != 0;
  }
  if (!loaded) return 0;
  const Real compliance = b.dot(factor_->ldlt.solve(b));
  return compliance > 0 && std::isfinite(compliance) ? 1 / compliance : 0;
}

}  // namespace felt
