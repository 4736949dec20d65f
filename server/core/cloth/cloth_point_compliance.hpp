#pragma once
// A cloth's stiffness at its points (PointCompliance), for the local model of a remote haptic
// device (issue 26). From the Jacobian of its springs and anchors in the shape it is in, with its
// pins held: across itself a cloth resists a push only by its springs' tension (their transverse
// stiffness k (1 − r/l), ForceJacobian), which a flat cloth at rest does not have, so the shape
// at rest says nothing of it and the shape now must be used.

#include "core/cloth/cloth_body.hpp"
#include "core/math/point_compliance.hpp"

namespace felt {

/// What `body`'s point compliance is factored from: the Jacobian of its springs and anchors at
/// its positions now, its pins held, its particles' masses.
ComplianceProblem compliance_problem(const ClothBody& body);

/// `body` at its positions now, at rest or over `horizon` (s, PointCompliance::factor); unknown
/// at rest when its springs leave a way to move that nothing resists (slack, or no pin or anchor
/// to hold it).
inline PointCompliance point_compliance(const ClothBody& body, Real horizon = 0) {
  return PointCompliance::factor(compliance_problem(body), horizon);
}

}  // namespace felt
