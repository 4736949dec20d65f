#include "core/solids/solid_collider_contact.hpp"

#include <algorithm>

#include "core/solids/contact_surface.hpp"

namespace felt {

std::size_t resolve_collider_contacts(std::span<const Collider> colliders, SolidBody& body) {
  std::vector<Vec3>& x = body.positions();
  std::vector<Vec3>& x_prev = body.previous_positions();
  std::size_t contacts = 0;
  for (const Collider& collider : colliders) {
    const Real mu = mixed_friction(collider.friction, body.material().friction);
    for (std::size_t n = 0; n < x.size(); ++n) {
      if (body.inv_mass()[n] == 0) continue;
      const SignedDistance sd = signed_distance(collider, x[n]);
      if (sd.distance >= 0) continue;
      ++contacts;
      const Vec3 push = -sd.distance * sd.normal;
      x[n] += push;
      x_prev[n] += push;
      const Vec3 motion = x[n] - x_prev[n];
      const Real approach = -motion.dot(sd.normal);
      if (approach <= 0) continue;
      x_prev[n] -= approach * sd.normal;
      const Vec3 tangential = motion + approach * sd.normal;
      const Real slide = tangential.norm();
      if (slide > 0) x[n] -= std::min(slide, mu * approach) / slide * tangential;
    }
  }
  return contacts;
}

}  // namespace felt
