#include "core/haptics/proxy_force.hpp"

#include <cmath>

#include "core/haptics/proxy_skin.hpp"
#include "core/haptics/triangle_placement.hpp"
#include "core/math/clamp_length.hpp"

namespace felt {
namespace {

/// The force on the device before damping and the device's limits. `held` is how far friction
/// holds the proxy from where it would slide to.
Vec3 spring_force(Real stiffness, const Vec3& offset, const Vec3& shaded, const Vec3& held) {
  if (shaded.isZero()) return stiffness * offset;
  // Ruspini's sub-proxy: the device projected onto the plane through the proxy with the shaded
  // normal, moved along that plane by what friction holds
  return stiffness * (shaded * shaded.dot(offset) + held - shaded * shaded.dot(held));
}

/// The vertex normals of `triangle` interpolated at `barycentric`, unit, turned to the side of
/// `normal` (every surface is two-sided); zero when they cancel.
Vec3 shaded_normal(const HapticSurface& surface, const HapticBody& body, std::uint32_t triangle,
                   const Vec3& barycentric, const Vec3& normal) {
  const Triangle& tri = body.triangles[triangle];
  Vec3 shaded = barycentric.x() * surface.normal(body, tri[0]) +
                barycentric.y() * surface.normal(body, tri[1]) +
                barycentric.z() * surface.normal(body, tri[2]);
  const Real length = shaded.norm();
  shaded = length > 0 && std::isfinite(length) ? Vec3(shaded / length) : Vec3::Zero();
  return shaded.dot(normal) < 0 ? Vec3(-shaded) : shaded;
}

}  // namespace

RenderedContact render_contact(const HapticSurface& surface, const CandidateTriangles& candidates,
                               const ProxySettings& settings,
                               const std::optional<NearestTriangle>& nearest, const ProxyRest& rest,
                               const Vec3& device, Real radius, Real dt,
                               const ForceHistory& history) {
  RenderedContact rendered;
  HapticContact& out = rendered.contact;
  Vec3 proxy = rest.position;
  Vec3 force = Vec3::Zero();
  Vec3 offset = Vec3::Zero();
  const bool in_contact = rest.frictionless != device;
  if (in_contact) {
    out.in_contact = true;
    out.constraints = rest.constraints;
    out.contact_point = rest.position;
    Vec3 shaded = Vec3::Zero();
    if (nearest && nearest->distance > 0) {
      const std::size_t i = nearest->candidate;
      const Vec3 normal = contact_normal(rest.position, candidates.corners(i), nearest->point);
      // drop the skin: the reported proxy touches at exactly the radius
      if (nearest->distance >= radius && nearest->distance <= radius + 2 * kProxySkin) {
        proxy = nearest->point.point + radius * normal;
      }
      const HapticBody& body = surface.bodies[candidates.body(i)];
      out.contact_point = nearest->point.point;
      out.normal = normal;
      out.body_id = body.body_id;
      out.triangle = static_cast<std::int32_t>(candidates.triangle(i));
      out.barycentric = nearest->point.barycentric;
      if (settings.force_shading && out.constraints == 1 &&
          body.normals_from.size() == body.from.size() &&
          body.normals_to.size() == body.from.size()) {
        shaded = shaded_normal(surface, body, candidates.triangle(i), out.barycentric, normal);
      }
    }
    offset = proxy - device;
    force = spring_force(settings.stiffness, offset, shaded, rest.position - rest.frictionless);
    if (history.in_contact && dt > 0 && std::isfinite(dt)) {
      force += settings.damping * (offset - history.offset) / dt;
    }
    // damping may slow the push, never pull the device into the surface
    if (force.dot(out.normal) < 0) force -= out.normal * force.dot(out.normal);
    if (!shaded.isZero()) out.normal = shaded;
  } else {
    out.contact_point = device;
  }

  // the device's limits
  force = clamp_length(force, settings.max_force);
  const Vec3 change = force - history.force;
  if (settings.max_force_change > 0 && change.norm() > settings.max_force_change) {
    force = history.force + clamp_length(change, settings.max_force_change);
  }
  out.force = force;
  out.proxy = proxy;
  out.slipping = rest.slipping;
  rendered.next = {in_contact, offset, force};
  return rendered;
}

}  // namespace felt
