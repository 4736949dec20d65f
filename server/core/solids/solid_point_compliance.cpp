#include "core/solids/solid_point_compliance.hpp"

#include <vector>

namespace felt {

PointCompliance point_compliance(const SolidBody& body, std::span<const Collider> colliders,
                                 Real horizon) {
  const Eigen::SparseMatrix<Real>* stiffness = body.rest_stiffness();
  if (!stiffness) return {};
  const std::vector<Vec3>& x = body.positions();
  std::vector<bool> held(x.size());
  std::vector<Real> mass(x.size());
  for (std::uint32_t n = 0; n < x.size(); ++n) {
    held[n] = body.inv_mass()[n] == 0;
    for (const Collider& collider : colliders) {
      held[n] = held[n] || signed_distance(collider, x[n]).distance <= kSupportDistance;
    }
    mass[n] = body.mass(n);
  }
  return PointCompliance::factor(*stiffness, std::move(held), mass, horizon);
}

}  // namespace felt
