#include "runtime/haptic_proxy.hpp"

#include <algorithm>

#include "core/collision/sphere_contact.hpp"
#include "core/math/aabb.hpp"
#include "core/math/bounds.hpp"
#include "core/math/clamp_length.hpp"

namespace felt {

Vec3 HapticProxy::starting_point(const HapticSurface& surface, const Vec3& device) const {
  std::optional<SphereContact> deepest;
  std::vector<Vec3> positions;
  std::vector<std::uint32_t> near;
  std::vector<Triangle> near_triangles;
  const Aabb sphere{device.array() - settings_.radius, device.array() + settings_.radius};
  for (const HapticBody& body : surface.bodies) {
    // only the triangles the body's structure finds near the sphere: all of them took the
    // network thread 0.3 ms per 20,000 (and its other clients waited)
    near.clear();
    body.query->collect(sphere, near);
    if (near.empty()) continue;
    // in index order, as brute force sees them, so that ties go the same way whatever the
    // structure
    std::sort(near.begin(), near.end());
    near_triangles.clear();
    for (const std::uint32_t t : near) {
      if (t < body.triangles.size()) near_triangles.push_back(body.triangles[t]);
    }
    positions.resize(body.to.size());
    for (std::uint32_t i = 0; i < positions.size(); ++i) positions[i] = surface.vertex(body, i);
    const auto contact = find_sphere_contact(positions, near_triangles, device, settings_.radius);
    if (contact && (!deepest || contact->depth > deepest->depth)) deepest = contact;
  }
  return deepest ? Vec3(device + deepest->depth * deepest->normal) : device;
}

Vec3 HapticProxy::grab_force(const HapticSurface& surface, const Vec3& device) const {
  const HapticBody& body = *surface.find(grab_->body);
  return clamped_spring_force(settings_.stiffness, surface.vertex(body, grab_->vertex) - device,
                              settings_.max_force);
}

Real HapticProxy::seconds_since_last(SteadyClock::time_point now) {
  const Real dt = last_update_ == SteadyClock::time_point{}
                      ? 0
                      : std::chrono::duration<Real>(now - last_update_).count();
  last_update_ = now;
  return dt;
}

void HapticProxy::forget_surface_if_idle(SteadyClock::time_point now, SteadyClock::duration idle) {
  if (god_ && last_update_ != SteadyClock::time_point{} && now - last_update_ > idle) {
    god_->forget_previous_surface();
  }
}

ProxyOutput HapticProxy::hold(ReactionAccumulator& reactions) const {
  ProxyOutput out;
  out.contact.proxy = out.contact.contact_point = god_ ? god_->proxy() : Vec3::Zero();
  if (grab_) {
    out.grabbing = true;
    out.grabbed_body = grab_->body;
    out.grabbed_vertex = grab_->vertex;
  }
  reactions.record(key_, ProxySample{});
  return out;
}

std::optional<ContactSpring> HapticProxy::contact_spring(
    const HapticSurface& surface, const HapticBody& body, const Triangle& corners,
    const Vec3& barycentric, const Vec3& proxy, const Vec3& device, const Vec3& normal) const {
  ContactSpring spring;
  // along the normal the force is shaded with, else along the spring itself
  spring.normal = normal.norm() > 0 ? normal.normalized() : Vec3((proxy - device).normalized());
  spring.stretch = (proxy - device).dot(spring.normal);
  if (!(spring.stretch > 0) || !(settings_.stiffness > 0) || !spring.normal.allFinite()) {
    return std::nullopt;
  }
  for (int c = 0; c < 3; ++c) spring.contact += barycentric[c] * surface.vertex(body, corners[c]);
  spring.max_force = settings_.max_force;
  spring.stiffness = settings_.stiffness;
  spring.device = device;
  return spring;
}

std::optional<Collider> HapticProxy::finger(const Vec3& centre) const {
  if (!(settings_.radius > 0)) return std::nullopt;
  Collider sphere;
  sphere.shape = Collider::Shape::kSphere;
  sphere.center = centre;
  sphere.radius = 0.5 * settings_.radius;
  sphere.friction = settings_.dynamic_friction;
  return sphere;
}

ProxySample HapticProxy::local_sample(const HapticSurface& surface, const Vec3& device,
                                      const LocalContact& local) const {
  ProxySample sample;
  const HapticBody* body = surface.find(local.body_id);
  // a triangle the surface no longer has (the body went, the scene was reset) pushes nothing
  if (local.in_contact && body && local.triangle >= 0 &&
      static_cast<std::size_t>(local.triangle) < body->triangles.size()) {
    const Real stiffness = std::min(local.stiffness, settings_.stiffness);
    const Vec3 force = clamped_spring_force(stiffness, local.proxy - device, settings_.max_force);
    // as felt, held as it is: the client renders against its own copy of the surface, seconds
    // of which may lie between its contact and this one (its renderer keeps the contact
    // passive, passive_stiffness)
    sample.push =
        ProxySample::Push{local.body_id, body->triangles[static_cast<std::size_t>(local.triangle)],
                          local.barycentric, -force, std::nullopt};
  }
  sample.sphere = finger(local.proxy);
  return sample;
}

void HapticProxy::estimate_stiffness(const HapticSurface& surface, const LocalContact& local,
                                     const Vec3& push, ProxyOutput& out) {
  const HapticBody* body = surface.find(local.body_id);
  if (!local.in_contact || !body || local.triangle < 0 ||
      static_cast<std::size_t>(local.triangle) >= body->triangles.size()) {
    estimated_body_.reset();
    return;
  }
  if (estimated_body_ != local.body_id) {
    stiffness_estimate_.reset();
    estimated_body_ = local.body_id;
  }
  const Triangle& corners = body->triangles[static_cast<std::size_t>(local.triangle)];
  Vec3 point = Vec3::Zero();
  for (int i = 0; i < 3; ++i) point += local.barycentric[i] * surface.vertex(*body, corners[i]);
  // along the normal from the touched point to the proxy resting on it
  const Vec3 outward = local.proxy - point;
  if (!(outward.norm() > 0)) return;
  const Vec3 normal = outward.normalized();
  stiffness_estimate_.add(push.dot(normal), point.dot(normal));
  out.pushed_body = local.body_id;
  out.pushed_body_stiffness = stiffness_estimate_.stiffness();
}

ProxyOutput HapticProxy::update(const HapticSurface& surface, Real dt, const Vec3& device,
                                std::uint32_t buttons, ReactionAccumulator& reactions,
                                const LocalContact* local) {
  if (!within_bounds(device)) return hold(reactions);
  if (!god_) god_.emplace(settings_, starting_point(surface, device));

  ProxyOutput out;
  out.contact = god_->update(surface, device, dt);
  const bool button_down = (buttons & kGrabButton) != 0;
  if (!button_down) grab_.reset();
  // a grab starts when the button is down and the proxy touches something: pressing first and
  // then touching grabs too
  if (button_down && !grab_ && out.contact.in_contact && out.contact.triangle >= 0) {
    const HapticBody& body = *surface.find(out.contact.body_id);
    const Triangle& corners = body.triangles[static_cast<std::size_t>(out.contact.triangle)];
    int nearest = 0;
    out.contact.barycentric.maxCoeff(&nearest);
    grab_ = Grab{out.contact.body_id, corners[nearest]};
  }
  // a grabbed body that is gone (removed, or the scene reset) ends the grab too
  if (grab_ &&
      (!surface.find(grab_->body) || grab_->vertex >= surface.find(grab_->body)->to.size())) {
    grab_.reset();
  }

  ProxySample sample;
  if (grab_) {
    out.grabbing = true;
    out.grabbed_body = grab_->body;
    out.grabbed_vertex = grab_->vertex;
    out.contact.force = grab_force(surface, device);
    if (!out.contact.force.allFinite()) return hold(reactions);  // a grabbed vertex gone bad
    sample.push =
        ProxySample::Push{grab_->body, Triangle{grab_->vertex, grab_->vertex, grab_->vertex},
                          Vec3(1, 0, 0), -out.contact.force, std::nullopt};
    sample.grab =
        GrabSpring{grab_->body, grab_->vertex, device, settings_.stiffness, settings_.damping};
  } else if (local) {
    sample = local_sample(surface, device, *local);
    if (sample.push) out.local_push = -sample.push->force;
    estimate_stiffness(surface, *local, out.local_push, out);
  } else {
    if (out.contact.in_contact && out.contact.triangle >= 0) {
      const HapticBody& body = *surface.find(out.contact.body_id);
      const Triangle& corners = body.triangles[static_cast<std::size_t>(out.contact.triangle)];
      sample.push = ProxySample::Push{
          out.contact.body_id, corners, out.contact.barycentric, -out.contact.force,
          contact_spring(surface, body, corners, out.contact.barycentric, out.contact.proxy, device,
                         out.contact.normal)};
    }
    // the finger takes room: vertices cannot move into the inner half of the proxy's sphere,
    // so a cloth pressed hard wraps around it instead of folding into it; the outer half is
    // left to the god-object, which must touch the surface first to feel it (a grabbed vertex
    // hangs inside the sphere, so there is none while grabbing)
    sample.sphere = finger(out.contact.proxy);
  }
  reactions.record(key_, sample);
  return out;
}

}  // namespace felt
