#include "local_renderer.hpp"

#include <algorithm>
#include <cmath>

#include "core/haptics/passive_stiffness.hpp"
#include "core/haptics/yielding_contact.hpp"

namespace felt::client {
namespace {

felt::ProxySettings core_settings(const felt::v1::ProxySettings& s) {
  felt::ProxySettings out;
  out.radius = s.radius();
  out.stiffness = s.stiffness();
  out.damping = s.damping();
  out.max_force = s.max_force();
  out.max_force_change = s.max_force_change();
  out.static_friction = s.static_friction();
  out.dynamic_friction = s.dynamic_friction();
  out.force_shading = s.force_shading();
  return out;
}

void put(const felt::Vec3& v, felt::v1::Vec3& out) {
  out.set_x(v.x());
  out.set_y(v.y());
  out.set_z(v.z());
}

/// The i-th of the vectors packed x y z in `packed`.
felt::Vec3 packed_at(const google::protobuf::RepeatedField<double>& packed, int i) {
  return {packed[3 * i], packed[3 * i + 1], packed[3 * i + 2]};
}

}  // namespace

LocalRenderer::LocalRenderer(const felt::v1::ProxySettings& settings,
                             const LocalRendererOptions& options)
    : settings_(core_settings(settings)), options_(options) {}

void LocalRenderer::take(const felt::LocalModel& model, double time, double round_trip) {
  surface_.take(model, time);
  model_push_ = model.push;
  surface_stiffness_.clear();
  for (const felt::LocalModelBody& body : model.bodies) {
    surface_stiffness_.emplace_back(body.body_id, body.stiffness);
  }
  if (std::isfinite(round_trip) && round_trip >= 0) delay_ = round_trip;
}

LocalForce LocalRenderer::tick(const felt::Vec3& device, double time) {
  if (!surface_.has_model()) {
    last_ = LocalForce{};
    last_.contact.proxy = last_.contact.contact_point = device;
    return last_;
  }
  // the surface touched last tick says how late its give comes (none touched: unknown)
  const double touched_stiffness =
      last_.contact.in_contact ? surface_stiffness(last_.contact.body_id) : 0;
  felt::ProxySettings settings = settings_;
  settings.stiffness = felt::passive_stiffness(settings_.stiffness, options_.device_damping,
                                               options_.servo_period, delay_, touched_stiffness);
  const double since = god_ ? time - last_time_ : 0;
  if (!god_) god_.emplace(settings, device);
  god_->set_settings(settings);
  // a tick that comes late (the device loop descheduled for 4 ms on a loaded machine) renders
  // the ticks it missed first, the device moving linearly between the two: in one step the
  // surface would move that many ticks' worth (a blend's share of centimetres), more than the
  // god-object's carry follows on a turning triangle
  const double periods = options_.servo_period > 0 ? since / options_.servo_period : 1;
  const int steps =
      periods > 1.5 ? static_cast<int>(std::min<double>(std::round(periods), kMaxCatchUpTicks)) : 1;
  const double dt = since / steps;
  for (int k = 1; k < steps; ++k) {
    const double s = static_cast<double>(k) / steps;
    god_->update(surface_.advance(last_time_ + s * since),
                 last_device_ + s * (device - last_device_), dt);
  }
  last_time_ = time;
  last_device_ = device;
  const felt::HapticContact contact = god_->update(surface_.advance(time), device, dt);
  last_.contact = felt::yielding_contact(contact, model_push_, settings.stiffness,
                                         surface_stiffness(contact.body_id));
  last_.stiffness = settings.stiffness;
  return last_;
}

double LocalRenderer::surface_stiffness(std::uint32_t body_id) const {
  for (const auto& [id, stiffness] : surface_stiffness_) {
    if (id == body_id) return stiffness;
  }
  return 0;
}

felt::v1::LocalContact LocalRenderer::upstream() const {
  felt::v1::LocalContact out;
  const felt::HapticContact& c = last_.contact;
  out.set_in_contact(c.in_contact && c.triangle >= 0 && last_.stiffness > 0);
  out.set_body_id(c.body_id);
  out.set_triangle(c.triangle);
  put(c.barycentric, *out.mutable_barycentric());
  put(c.proxy, *out.mutable_proxy());
  out.set_stiffness(last_.stiffness);
  return out;
}

std::optional<felt::LocalModel> local_model_from(const felt::v1::LocalModel& model) {
  felt::LocalModel out;
  out.truncated = model.truncated();
  if (model.has_push()) out.push = {model.push().x(), model.push().y(), model.push().z()};
  for (const felt::v1::LocalModelBody& wire : model.bodies()) {
    const int vertices = wire.vertex_ids_size();
    const int triangles = wire.triangle_ids_size();
    if (wire.vertex_count() > felt::kMaxLocalModelSurface ||
        wire.triangle_count() > felt::kMaxLocalModelSurface ||
        wire.corners_size() != 3 * triangles || wire.positions_size() != 3 * vertices ||
        wire.velocities_size() != 3 * vertices || wire.normals_size() != 3 * vertices) {
      return std::nullopt;
    }
    felt::LocalModelBody& body = out.bodies.emplace_back();
    body.body_id = wire.body_id();
    body.vertex_count = wire.vertex_count();
    body.triangle_count = wire.triangle_count();
    body.stiffness = wire.stiffness();
    body.triangle_ids.assign(wire.triangle_ids().begin(), wire.triangle_ids().end());
    for (int t = 0; t < triangles; ++t) {
      body.corners.push_back(
          {wire.corners(3 * t), wire.corners(3 * t + 1), wire.corners(3 * t + 2)});
    }
    body.vertex_ids.assign(wire.vertex_ids().begin(), wire.vertex_ids().end());
    for (int i = 0; i < vertices; ++i) {
      body.positions.push_back(packed_at(wire.positions(), i));
      body.velocities.push_back(packed_at(wire.velocities(), i));
      body.normals.push_back(packed_at(wire.normals(), i));
    }
  }
  if (!felt::well_formed(out)) return std::nullopt;
  return out;
}

double local_model_time(const felt::v1::LocalModel& model, double received, double round_trip) {
  const double age = std::isfinite(model.age_s()) ? model.age_s() : 0;
  return received - age - 0.5 * round_trip;
}

}  // namespace felt::client
