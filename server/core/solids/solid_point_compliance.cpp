#include "core/solids/solid_point_compliance.hpp"

#include <vector>

namespace felt {

std::optional<ComplianceProblem> compliance_problem(const SolidBody& body,
                                                    std::span<const Collider> colliders) {
  const Eigen::SparseMatrix<Real>* stiffness = body.rest_stiffness();
  if (!stiffness) return std::nullopt;
  const std::vector<Vec3>& x = body.positions();
  ComplianceProblem problem{*stiffness, std::vector<bool>(x.size()), std::vector<Real>(x.size())};
  for (std::uint32_t n = 0; n < x.size(); ++n) {
    problem.held[n] = body.inv_mass()[n] == 0;
    for (const Collider& collider : colliders) {
      problem.held[n] =
          problem.held[n] || signed_distance(collider, x[n]).distance <= kSupportDistance;
    }
    problem.mass[n] = body.mass(n);
  }
  return problem;
}

}  // namespace felt
