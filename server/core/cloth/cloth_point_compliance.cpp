#include "core/cloth/cloth_point_compliance.hpp"

#include <vector>

#include "core/integrate/force_jacobian.hpp"

namespace felt {

ComplianceProblem compliance_problem(const ClothBody& body) {
  const std::vector<Vec3>& x = body.state().x;
  ForceJacobian jacobian;
  body.compute_jacobian(x, body.state().v, jacobian);
  const std::vector<Real> unscaled(x.size(), 1);
  ComplianceProblem problem;
  Eigen::SparseMatrix<Real> damping;
  jacobian.scaled_matrices(unscaled, problem.stiffness, damping);
  problem.held.resize(x.size());
  for (std::uint32_t p = 0; p < x.size(); ++p) problem.held[p] = body.is_pinned(p);
  problem.mass = body.model().mass;
  return problem;
}

}  // namespace felt
