#include "core/haptics/proxy_friction.hpp"

#include <algorithm>

#include "core/haptics/candidate_sweep.hpp"
#include "core/haptics/proxy_skin.hpp"

namespace felt {

FrictionStop hold_by_friction(const HapticSurface& surface, CandidateTriangles& candidates,
                              const ProxySettings& settings, const ConstrainedMove& frictionless,
                              const Vec3& start, const Vec3& device, Real radius,
                              bool was_in_contact, bool was_slipping) {
  const Vec3& rest = frictionless.position;
  const Real mu_static = std::max(settings.static_friction, Real{0});
  const Real mu_dynamic = std::max(settings.dynamic_friction, Real{0});
  if (!(mu_static > 0 || mu_dynamic > 0)) return {rest, false};
  const Vec3 stuck = was_in_contact ? start : frictionless.first_stop.value_or(start);
  const Real depth = std::max((rest - device).norm() - kProxySkin, Real{0});  // as felt
  const Real drift = (stuck - rest).norm();
  const bool slipping =
      mu_dynamic > mu_static || drift > (was_slipping ? mu_dynamic : mu_static) * depth;
  if (!slipping || !(drift > mu_dynamic * depth)) return {stuck, slipping};
  // dragged until the device lies on the dynamic cone: back from where it would slide toward
  // where it stuck, both places it may be, along the surface between them
  const Vec3 target = rest + (stuck - rest) * (mu_dynamic * depth / drift);
  candidates.gather(surface, segment_box(rest, target, radius + kProxySkin));
  return {sweep_to(candidates, rest, target, radius).position, true};
}

}  // namespace felt
