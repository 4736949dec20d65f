#include "core/haptics/god_object.hpp"

#include <algorithm>
#include <cmath>

#include "core/haptics/constrained_move.hpp"
#include "core/haptics/proxy_friction.hpp"
#include "core/haptics/proxy_skin.hpp"
#include "core/math/bounds.hpp"

namespace felt {

GodObject::GodObject(const ProxySettings& settings, const Vec3& device)
    : settings_(settings), proxy_(device), rest_(device) {}

HapticContact GodObject::hold() {
  history_.force = Vec3::Zero();
  HapticContact out;
  out.proxy = proxy_;
  out.contact_point = proxy_;
  return out;
}

HapticContact GodObject::update(const HapticSurface& surface, const Vec3& device, Real dt) {
  if (!within_bounds(device)) return hold();
  const Real radius = std::isfinite(settings_.radius) ? std::max(settings_.radius, Real{0}) : 0;
  candidates_.forget();
  carry_.follow(surface);
  // how far the surface may move before the next update, as far as it moved in its last step:
  // the anchor looks that far
  Real motion = 0;
  for (const HapticBody& body : surface.bodies) motion = std::max(motion, body.displacement());
  // one box for what most updates look at: the proxy carried by the surface's motion since the
  // previous update, its slide toward the device, the surface within the anchor's reach
  candidates_.gather(
      surface, segment_box(rest_, device, radius + 2 * kProxySkin + carry_.margin() + motion));

  // leg 1: carried with the surface
  const Vec3 start = carry_.carry(surface, candidates_, rest_, anchor_);
  // leg 2: slid toward the device, then held by friction
  const ConstrainedMove frictionless = move_proxy(surface, candidates_, start, device, radius);
  const bool in_contact = frictionless.position != device;
  const FrictionStop friction =
      in_contact ? hold_by_friction(surface, candidates_, settings_, frictionless, start, device,
                                    radius, history_.in_contact, slipping_)
                 : FrictionStop{frictionless.position, false};
  // what it touches, and the triangle it is anchored to until the next update
  const Touch touch = find_touch(surface, candidates_, friction.rest, radius, motion);
  const RenderedContact rendered = render_contact(
      surface, candidates_, settings_, touch.nearest,
      {friction.rest, frictionless.position, frictionless.constraints, friction.slipping}, device,
      radius, dt, history_);

  // nothing non-finite leaves (a surface too large for doubles): keep the proxy where it was
  if (!rendered.contact.finite() || !friction.rest.allFinite()) return hold();
  rest_ = friction.rest;
  proxy_ = rendered.contact.proxy;
  anchor_ = touch.anchor;
  carry_.remember(surface);  // its storage too: kept until the next update
  slipping_ = friction.slipping;
  history_ = rendered.next;
  return rendered.contact;
}

}  // namespace felt
