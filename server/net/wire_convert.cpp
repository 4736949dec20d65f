#include "net/wire_convert.hpp"

namespace felt::net {

namespace v1 = felt::v1;

namespace {

void put_vectors(const std::vector<Vec3>& vectors, google::protobuf::RepeatedField<double>& out) {
  out.Reserve(static_cast<int>(3 * vectors.size()));
  for (const Vec3& v : vectors) {
    for (int k = 0; k < 3; ++k) out.AddAlreadyReserved(v[k]);
  }
}

std::expected<std::vector<Vec3>, std::string> to_vectors(
    const google::protobuf::RepeatedField<double>& values, const char* what) {
  if (values.size() % 3 != 0) {
    return std::unexpected(std::string(what) + " must come in threes (x, y, z)");
  }
  std::vector<Vec3> vectors(static_cast<std::size_t>(values.size() / 3));
  for (std::size_t i = 0; i < vectors.size(); ++i) {
    vectors[i] = Vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
  }
  return vectors;
}

v1::EventKind event_kind(SceneEvent::Kind kind) {
  using K = SceneEvent::Kind;
  switch (kind) {
    case K::kUnrecoverableStep:
      return v1::EVENT_KIND_UNRECOVERABLE_STEP;
    case K::kRescuedStep:
      return v1::EVENT_KIND_STEP_RESCUED;
    case K::kOverBudgetStep:
      return v1::EVENT_KIND_STEP_OVER_BUDGET;
    case K::kBodyAdded:
      return v1::EVENT_KIND_BODY_ADDED;
    case K::kBodyRemoved:
      return v1::EVENT_KIND_BODY_REMOVED;
    case K::kBodyChanged:
      return v1::EVENT_KIND_BODY_CHANGED;
    case K::kPaused:
      return v1::EVENT_KIND_SCENE_PAUSED;
    case K::kResumed:
      return v1::EVENT_KIND_SCENE_RESUMED;
    case K::kReset:
      return v1::EVENT_KIND_SCENE_RESET;
    case K::kStateRestored:
      return v1::EVENT_KIND_STATE_RESTORED;
    case K::kTimeScale:
      return v1::EVENT_KIND_TIME_SCALE;
    case K::kDestroyed:
      return v1::EVENT_KIND_SCENE_DESTROYED;
    case K::kClientJoined:
      return v1::EVENT_KIND_CLIENT_JOINED;
    case K::kClientLeft:
      return v1::EVENT_KIND_CLIENT_LEFT;
  }
  return v1::EVENT_KIND_UNSPECIFIED;
}

}  // namespace

void put_vec3(const Vec3& v, v1::Vec3& out) {
  out.set_x(v.x());
  out.set_y(v.y());
  out.set_z(v.z());
}

Vec3 to_vec3(const v1::Vec3& v) {
  return Vec3(v.x(), v.y(), v.z());
}

void fill_error(std::uint64_t request_id, v1::ErrorCode code, const std::string& message,
                v1::ServerMessage& out) {
  out.set_request_id(request_id);
  v1::Error* error = out.mutable_error();
  error->set_code(code);
  error->set_message(message);
  error->set_request_id(request_id);
}

v1::ErrorCode error_code(RunnerError::Code code) {
  using C = RunnerError::Code;
  switch (code) {
    case C::kBadRequest:
      return v1::ERROR_CODE_BAD_REQUEST;
    case C::kUnknownId:
      return v1::ERROR_CODE_UNKNOWN_ID;
    case C::kWrongState:
      return v1::ERROR_CODE_WRONG_STATE;
    case C::kLimitExceeded:
      return v1::ERROR_CODE_LIMIT_EXCEEDED;
    case C::kCancelled:
      return v1::ERROR_CODE_CANCELLED;
    case C::kBadScene:
      return v1::ERROR_CODE_BAD_SCENE;
  }
  return v1::ERROR_CODE_INTERNAL;
}

void fill_body_info(const BodyInfo& body, v1::BodyInfo& out) {
  out.set_body_id(body.body_id.value());
  out.set_name(body.name);
  out.set_kind(body.kind);
  out.set_particles(body.particles);
  out.set_triangles(body.triangles);
  out.set_owner(body.owner.value());
  out.set_nodes(body.nodes);
  if (body.collider) fill_collider(*body.collider, *out.mutable_collider());
}

void fill_collider(const Collider& collider, v1::ColliderShape& out) {
  switch (collider.shape) {
    case Collider::Shape::kPlane:
      out.set_kind(v1::COLLIDER_KIND_PLANE);
      put_vec3(collider.normal, *out.mutable_normal());
      break;
    case Collider::Shape::kSphere:
      out.set_kind(v1::COLLIDER_KIND_SPHERE);
      out.set_radius(collider.radius);
      break;
    case Collider::Shape::kBox:
      out.set_kind(v1::COLLIDER_KIND_BOX);
      put_vec3(collider.half_extents, *out.mutable_half_extents());
      break;
    case Collider::Shape::kCapsule:
      out.set_kind(v1::COLLIDER_KIND_CAPSULE);
      put_vec3(collider.end, *out.mutable_end());
      out.set_radius(collider.radius);
      break;
  }
  put_vec3(collider.center, *out.mutable_center());
  out.set_friction(collider.friction);
}

void fill_event(SceneId scene, const SceneEvent& event, v1::SceneEvent& out) {
  out.set_scene_id(scene.value());
  out.set_sequence(event.sequence);
  out.set_kind(event_kind(event.kind));
  out.set_step(event.step);
  out.set_sim_time(event.sim_time);
  out.set_count(event.count);
  for (BodyId id : event.body_ids) out.add_body_ids(id.value());
  out.set_client_id(event.client.value());
  out.set_client_name(event.client_name);
  for (const BodyInfo& body : event.bodies) fill_body_info(body, *out.add_bodies());
  out.set_time_scale(event.time_scale);
}

void fill_status(SceneId scene, const SceneStatus& status, v1::SceneStatus& out) {
  out.set_scene_id(scene.value());
  out.set_step(status.step);
  out.set_sim_time(status.sim_time);
  out.set_paused(status.paused);
  out.set_time_scale(status.time_scale);
}

void fill_proxy_settings(const ProxySettings& settings, v1::ProxySettings& out) {
  out.set_radius(settings.radius);
  out.set_stiffness(settings.stiffness);
  out.set_max_force(settings.max_force);
  out.set_damping(settings.damping);
  out.set_max_force_change(settings.max_force_change);
  out.set_static_friction(settings.static_friction);
  out.set_dynamic_friction(settings.dynamic_friction);
  out.set_force_shading(settings.force_shading);
}

void fill_state(const WorldState& state, Real time_step, v1::SceneState& out) {
  out.set_step(state.step);
  out.set_sim_time(static_cast<double>(state.step) * time_step);
  for (const BodyMotionState& body : state.bodies) {
    v1::BodyState& b = *out.add_bodies();
    b.set_body_id(body.body_id.value());
    put_vectors(body.positions, *b.mutable_positions());
    put_vectors(body.velocities, *b.mutable_velocities());
    put_vectors(body.previous_positions, *b.mutable_previous_positions());
    for (std::uint32_t p : body.pinned) b.add_pinned(p);
    b.set_previous_step(body.previous_step);
  }
}

std::expected<std::shared_ptr<const WorldState>, std::string> to_state(
    const v1::SceneState& state) {
  auto out = std::make_shared<WorldState>();
  out->step = state.step();
  for (const v1::BodyState& b : state.bodies()) {
    BodyMotionState& body = out->bodies.emplace_back();
    body.body_id = b.body_id();
    auto positions = to_vectors(b.positions(), "positions");
    auto velocities = to_vectors(b.velocities(), "velocities");
    auto previous = to_vectors(b.previous_positions(), "previous_positions");
    for (auto* vectors : {&positions, &velocities, &previous}) {
      if (!*vectors)
        return std::unexpected("body " + std::to_string(b.body_id()) + ": " + vectors->error());
    }
    body.positions = std::move(*positions);
    body.velocities = std::move(*velocities);
    body.previous_positions = std::move(*previous);
    body.pinned.assign(b.pinned().begin(), b.pinned().end());
    body.previous_step = b.previous_step();
  }
  return out;
}

}  // namespace felt::net
