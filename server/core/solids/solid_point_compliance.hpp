#pragma once
// A solid's stiffness at its points (PointCompliance), for the local model of a remote haptic
// device (issue 26): its model's stiffness matrix at rest (corotated FEM, generalized mass-spring;
// shape matching has none), with its pins held and the nodes that rest on a collider held as
// well (a body on a floor is held by it: without that its matrix has the rigid motions in its
// null space and no static stiffness).

#include <optional>
#include <span>

#include "core/collision/collider.hpp"
#include "core/math/point_compliance.hpp"
#include "core/solids/solid_body.hpp"

namespace felt {

/// m: a node this close to a collider's surface (or inside it) rests on it.
inline constexpr Real kSupportDistance = 1e-3;

/// What `body`'s point compliance is factored from: its model's stiffness matrix at rest, its
/// pins and the nodes resting on `colliders` held, its nodes' masses; none for shape matching.
std::optional<ComplianceProblem> compliance_problem(const SolidBody& body,
                                                    std::span<const Collider> colliders);

/// `body` held by its pins and `colliders`, at rest or over `horizon` (s,
/// PointCompliance::factor); unknown for shape matching, and at rest for a body nothing holds.
inline PointCompliance point_compliance(const SolidBody& body, std::span<const Collider> colliders,
                                        Real horizon = 0) {
  const std::optional<ComplianceProblem> problem = compliance_problem(body, colliders);
  return problem ? PointCompliance::factor(*problem, horizon) : PointCompliance{};
}

}  // namespace felt
