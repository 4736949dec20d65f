#include "net/haptic_wire.hpp"

#include <cmath>

#include "core/math/bounds.hpp"
#include "net/wire_convert.hpp"

namespace felt::net {

std::uint64_t steady_ns(std::chrono::steady_clock::time_point t) {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count());
}

std::expected<LocalContact, std::string> local_contact(const v1::LocalContact& local,
                                                       const ProxySettings& settings) {
  LocalContact contact;
  contact.in_contact = local.in_contact();
  contact.body_id = local.body_id();
  contact.triangle = local.triangle();
  contact.barycentric = to_vec3(local.barycentric());
  contact.proxy = to_vec3(local.proxy());
  contact.stiffness = local.stiffness();
  if (!local.has_proxy() || !within_bounds(contact.proxy)) {
    return std::unexpected("local.proxy must be three numbers within ±1e6 m");
  }
  if (!contact.in_contact) return contact;
  // a contact point in its triangle, to rounding
  constexpr Real kSlack = 1e-6;
  if (!contact.barycentric.allFinite() || !(contact.barycentric.minCoeff() >= -kSlack) ||
      !(std::abs(contact.barycentric.sum() - 1) <= kSlack)) {
    return std::unexpected("local.barycentric must be three numbers >= 0 that sum to 1");
  }
  if (!(std::isfinite(contact.stiffness) && contact.stiffness > 0 &&
        contact.stiffness <= settings.stiffness)) {
    return std::unexpected("local.stiffness must be in (0, the proxy's stiffness]");
  }
  return contact;
}

void put_local_model(const LocalModelCut& cut, std::uint64_t send_ns, v1::LocalModel& out) {
  out.set_step(cut.step);
  const std::uint64_t rendered_ns = steady_ns(cut.rendered_at);
  out.set_age_s((static_cast<double>(send_ns) - static_cast<double>(rendered_ns)) * 1e-9);
  out.set_truncated(cut.model.truncated);
  if (!cut.model.push.isZero()) put_vec3(cut.model.push, *out.mutable_push());
  const auto put_all = [](const std::vector<Vec3>& from,
                          google::protobuf::RepeatedField<double>& to) {
    to.Reserve(static_cast<int>(3 * from.size()));
    for (const Vec3& v : from) {
      to.Add(v.x());
      to.Add(v.y());
      to.Add(v.z());
    }
  };
  for (const LocalModelBody& body : cut.model.bodies) {
    v1::LocalModelBody& wire = *out.add_bodies();
    wire.set_body_id(body.body_id);
    wire.set_vertex_count(body.vertex_count);
    wire.set_triangle_count(body.triangle_count);
    wire.mutable_triangle_ids()->Add(body.triangle_ids.begin(), body.triangle_ids.end());
    for (const Triangle& corners : body.corners) {
      wire.mutable_corners()->Add(corners.begin(), corners.end());
    }
    wire.mutable_vertex_ids()->Add(body.vertex_ids.begin(), body.vertex_ids.end());
    put_all(body.positions, *wire.mutable_positions());
    put_all(body.velocities, *wire.mutable_velocities());
    put_all(body.normals, *wire.mutable_normals());
    wire.set_stiffness(body.stiffness);
  }
}

void fill_force_update(const ProxyOutput& out, v1::ForceUpdate& force) {
  const HapticContact& contact = out.contact;
  put_vec3(contact.force, *force.mutable_force());
  put_vec3(contact.contact_point, *force.mutable_contact_point());
  force.set_in_contact(contact.in_contact);
  force.set_body_id(out.grabbing ? out.grabbed_body : contact.body_id);
  force.set_triangle(contact.triangle);
  put_vec3(contact.proxy, *force.mutable_proxy());
  put_vec3(contact.normal, *force.mutable_normal());
  force.set_constraints(static_cast<std::uint32_t>(contact.constraints));
  force.set_slipping(contact.slipping);
  force.set_grabbing(out.grabbing);
  force.set_grabbed_vertex(out.grabbed_vertex);
}

}  // namespace felt::net
