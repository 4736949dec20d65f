#pragma once
// How stiff each body of a local model is under the device's push (LocalModelBody::stiffness,
// issue 26): what the client's copy of the surface gives by (yielding_contact) and how much of
// its stiffness comes back late (passive_stiffness). Two sources: the body's own stiffness at the
// point, from its model (BodySnapshot::compliance: a cloth's springs, tension and pins, a solid's
// elements and supports), known before the first push; and the server's fit to the pushes
// (SurfaceStiffnessEstimate), which sees whatever the body does, but only after the push has
// varied, and which a body that swings away as a whole makes far too low.
//
// A spring in series stands for a surface that answers a push as a spring: where the point's
// stiffness under a push held for kComplianceHorizon is more than kInertialRatio times its
// static one, its inertia answers instead (the default curtain: 2-4 N/m at rest, 7-60 N/m over
// 50 ms), it swings on after the push and back, and the copy is better held rigid: 0 (unknown)
// is sent, whatever the fit says. Otherwise the larger of the static stiffness (everything else
// has settled: the body is not softer under a push it has had time to answer) and the fit
// (stiffer where damping or the contact's shape make it so). Without a model (shape matching, or a
// body too large for its snapshot to carry one: snapshot.cpp's kMaxComplianceNodes), the fit.

#include <cstdint>
#include <optional>

#include "core/haptics/local_model.hpp"
#include "runtime/haptic_proxy.hpp"
#include "runtime/snapshot.hpp"

namespace felt {

/// Above this ratio of the stiffness over kComplianceHorizon to the static stiffness a point
/// answers a push by its inertia.
inline constexpr Real kInertialRatio = 2;

/// What `body`'s own model says of its stiffness (N/m) at `touched`'s point (when it touches
/// `cut`'s body) or at `cut`'s vertex nearest `centre`, along the surface's normal there: nothing
/// without a model, 0 where the point answers a push by its inertia, else the static stiffness.
std::optional<Real> own_stiffness(const BodySnapshot& body, const LocalModelBody& cut,
                                  const Vec3& centre, const LocalContact* touched);

/// Sets the stiffness of every body of `model` (cut from `snapshot` around `centre`) from its
/// own_stiffness and, for the body `estimated`, the fit `estimate` (N/m; 0: unknown), as above.
void set_local_model_stiffness(LocalModel& model, const SceneSnapshot& snapshot, const Vec3& centre,
                               const LocalContact* touched, std::uint32_t estimated, Real estimate);

}  // namespace felt
