#include "runtime/proxy_contact.hpp"

#include "core/sphere_contact.hpp"

namespace felt {

ProxyContact solve_proxy_contact(const SceneSnapshot& snapshot, const ProxySettings& settings,
                                 const Vec3& position) {
  ProxyContact result;
  result.contact_point = position;
  Real deepest = 0;
  for (const BodySnapshot& body : snapshot.bodies) {
    const auto contact =
        find_sphere_contact(body.positions, body.triangles(), position, settings.radius);
    if (!contact || contact->depth <= deepest) continue;
    deepest = contact->depth;
    result.in_contact = true;
    result.body_id = body.body_id;
    result.triangle = static_cast<std::int32_t>(contact->triangle);
    result.barycentric = contact->barycentric;
    result.contact_point = contact->point;
    result.force = settings.stiffness * contact->depth * contact->normal;
  }
  const Real magnitude = result.force.norm();
  if (magnitude > settings.max_force) result.force *= settings.max_force / magnitude;
  return result;
}

}  // namespace felt
