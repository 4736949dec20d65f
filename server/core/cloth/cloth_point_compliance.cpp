#include "core/cloth/cloth_point_compliance.hpp"

#include <vector>

#include "core/integrate/force_jacobian.hpp"

namespace felt {

PointCompliance point_compliance(const ClothBody& body, Real horizon) {
  const std::vector<Vec3>& x = body.state().x;
  ForceJacobian jacobian;
  body.compute_jacobian(x, body.state().v, jacobian);
  const std::vector<Real> unscaled(x.size(), 1);
  Eigen::SparseMatrix<Real> stiffness, damping;
  jacobian.scaled_matrices(unscaled, stiffness, damping);
  std::vector<bool> held(x.size());
  for (std::uint32_t p = 0; p < x.size(); ++p) held[p] = body.is_pinned(p);
  return PointCompliance::factor(stiffness, std::move(held), body.model().mass, horizon);
}

}  // namespace felt
