// The typed requests of felt_client: each builds one ClientMessage and returns its reply.

#include "felt_client.hpp"

namespace felt::client {

namespace v1 = felt::v1;

namespace {

void put_point(const Point& p, v1::Vec3& out) {
  out.set_x(p[0]);
  out.set_y(p[1]);
  out.set_z(p[2]);
}

}  // namespace

v1::Welcome Client::hello(const std::string& client_name, const std::string& token) {
  v1::ClientMessage message;
  v1::Hello* hello = message.mutable_hello();
  hello->set_protocol_version(1);
  hello->set_client_name(client_name);
  hello->set_token(token);
  return request(message, v1::ServerMessage::kWelcome).welcome();
}

v1::Stats Client::stats() {
  v1::ClientMessage message;
  message.mutable_get_stats();
  return request(message, v1::ServerMessage::kStats).stats();
}

v1::SceneList Client::list_scenes() {
  v1::ClientMessage message;
  message.mutable_list_scenes();
  return request(message, v1::ServerMessage::kSceneList).scene_list();
}

v1::SceneLoaded Client::load_scene_by_name(const std::string& name, bool shared) {
  v1::ClientMessage message;
  message.mutable_load_scene()->set_name(name);
  message.mutable_load_scene()->set_shared(shared);
  return request(message, v1::ServerMessage::kSceneLoaded).scene_loaded();
}

v1::SceneLoaded Client::load_scene_json(const std::string& json, bool shared) {
  v1::ClientMessage message;
  message.mutable_load_scene()->set_json(json);
  message.mutable_load_scene()->set_shared(shared);
  return request(message, v1::ServerMessage::kSceneLoaded).scene_loaded();
}

v1::SceneLoaded Client::create_scene(const v1::CreateScene& create) {
  v1::ClientMessage message;
  *message.mutable_create_scene() = create;
  return request(message, v1::ServerMessage::kSceneLoaded).scene_loaded();
}

v1::SceneLoaded Client::join_scene(std::uint64_t scene_id) {
  v1::ClientMessage message;
  message.mutable_join_scene()->set_scene_id(scene_id);
  return request(message, v1::ServerMessage::kSceneLoaded).scene_loaded();
}

v1::SceneLeft Client::leave_scene() {
  v1::ClientMessage message;
  message.mutable_leave_scene();
  return request(message, v1::ServerMessage::kSceneLeft).scene_left();
}

v1::SceneDestroyed Client::destroy_scene(std::uint64_t scene_id) {
  v1::ClientMessage message;
  message.mutable_destroy_scene()->set_scene_id(scene_id);
  return request(message, v1::ServerMessage::kSceneDestroyed).scene_destroyed();
}

v1::SceneStatus Client::pause() {
  v1::ClientMessage message;
  message.mutable_pause_scene();
  return request(message, v1::ServerMessage::kSceneStatus).scene_status();
}

v1::SceneStatus Client::resume() {
  v1::ClientMessage message;
  message.mutable_resume_scene();
  return request(message, v1::ServerMessage::kSceneStatus).scene_status();
}

v1::SceneStatus Client::step(std::uint32_t steps) {
  v1::ClientMessage message;
  message.mutable_step_scene()->set_steps(steps);
  return request(message, v1::ServerMessage::kSceneStatus).scene_status();
}

v1::SceneStatus Client::set_time_scale(double scale) {
  v1::ClientMessage message;
  message.mutable_set_time_scale()->set_scale(scale);
  return request(message, v1::ServerMessage::kSceneStatus).scene_status();
}

v1::SceneStatus Client::reset() {
  v1::ClientMessage message;
  message.mutable_reset_scene();
  return request(message, v1::ServerMessage::kSceneStatus).scene_status();
}

v1::StateSaved Client::save_state(bool include_data) {
  v1::ClientMessage message;
  message.mutable_save_state()->set_include_data(include_data);
  return request(message, v1::ServerMessage::kStateSaved).state_saved();
}

v1::SceneStatus Client::restore_state(std::uint32_t state_id) {
  v1::ClientMessage message;
  message.mutable_restore_state()->set_state_id(state_id);
  return request(message, v1::ServerMessage::kSceneStatus).scene_status();
}

v1::SceneStatus Client::restore_state(const v1::SceneState& state) {
  v1::ClientMessage message;
  *message.mutable_restore_state()->mutable_data() = state;
  return request(message, v1::ServerMessage::kSceneStatus).scene_status();
}

v1::BodyAdded Client::add_body(const std::string& body_json) {
  v1::ClientMessage message;
  message.mutable_add_body()->set_body_json(body_json);
  return request(message, v1::ServerMessage::kBodyAdded).body_added();
}

v1::BodyAdded Client::add_collider(const std::string& collider_json) {
  v1::ClientMessage message;
  message.mutable_add_body()->set_collider_json(collider_json);
  return request(message, v1::ServerMessage::kBodyAdded).body_added();
}

v1::BodyRemoved Client::remove_body(std::uint32_t body_id) {
  v1::ClientMessage message;
  message.mutable_remove_body()->set_body_id(body_id);
  return request(message, v1::ServerMessage::kBodyRemoved).body_removed();
}

v1::BodyUpdated Client::set_body_parameters(const v1::SetBodyParameters& parameters) {
  v1::ClientMessage message;
  *message.mutable_set_body_parameters() = parameters;
  return request(message, v1::ServerMessage::kBodyUpdated).body_updated();
}

v1::BodyUpdated Client::pin_particles(std::uint32_t body_id, const std::vector<std::uint32_t>& pin,
                                      const std::vector<std::uint32_t>& unpin) {
  v1::ClientMessage message;
  v1::PinParticles* pins = message.mutable_pin_particles();
  pins->set_body_id(body_id);
  for (std::uint32_t p : pin) pins->add_pin(p);
  for (std::uint32_t p : unpin) pins->add_unpin(p);
  return request(message, v1::ServerMessage::kBodyUpdated).body_updated();
}

v1::BodyUpdated Client::apply_force(std::uint32_t body_id,
                                    const std::vector<std::uint32_t>& vertices, const Point& force,
                                    double duration) {
  v1::ClientMessage message;
  v1::ApplyForce* push = message.mutable_apply_force();
  push->set_body_id(body_id);
  for (std::uint32_t v : vertices) push->add_vertices(v);
  put_point(force, *push->mutable_force());
  push->set_duration(duration);
  return request(message, v1::ServerMessage::kBodyUpdated).body_updated();
}

v1::ProxyOpened Client::open_proxy(const v1::ProxySettings& settings) {
  v1::ClientMessage message;
  *message.mutable_open_proxy()->mutable_settings() = settings;
  return request(message, v1::ServerMessage::kProxyOpened).proxy_opened();
}

v1::ProxyClosed Client::close_proxy(std::uint32_t proxy_id) {
  v1::ClientMessage message;
  message.mutable_close_proxy()->set_proxy_id(proxy_id);
  return request(message, v1::ServerMessage::kProxyClosed).proxy_closed();
}

v1::ForceUpdate Client::proxy_update(std::uint32_t proxy_id, const Point& position,
                                     std::uint32_t buttons) {
  v1::ClientMessage message;
  v1::ProxyUpdate* update = message.mutable_proxy_update();
  update->set_proxy_id(proxy_id);
  put_point(position, *update->mutable_position());
  update->set_buttons(buttons);
  update->set_client_time_us(steady_microseconds());
  return request(message, v1::ServerMessage::kForceUpdate).force_update();
}

v1::Subscribed Client::subscribe_frames(double max_rate_hz, bool normals) {
  FrameSubscription subscription;
  subscription.max_rate_hz = max_rate_hz;
  subscription.normals = normals;
  return subscribe_frames(subscription);
}

v1::Subscribed Client::subscribe_frames(const FrameSubscription& subscription) {
  v1::ClientMessage message;
  v1::SubscribeFrames* subscribe = message.mutable_subscribe_frames();
  subscribe->set_max_rate_hz(subscription.max_rate_hz);
  subscribe->set_normals(subscription.normals);
  for (std::uint32_t body : subscription.body_ids) subscribe->add_body_ids(body);
  subscribe->set_encoding(subscription.quantized ? v1::FRAME_ENCODING_QUANTIZED16
                                                 : v1::FRAME_ENCODING_FLOAT32);
  subscribe->set_deltas(subscription.deltas);
  subscribe->set_scalars(subscription.scalars);
  subscribe->set_max_unacknowledged(subscription.max_unacknowledged);
  return request(message, v1::ServerMessage::kSubscribed).subscribed();
}

v1::Unsubscribed Client::unsubscribe_frames() {
  v1::ClientMessage message;
  message.mutable_unsubscribe_frames();
  return request(message, v1::ServerMessage::kUnsubscribed).unsubscribed();
}

v1::FrameAcked Client::ack_frame(std::uint64_t sequence) {
  v1::ClientMessage message;
  message.mutable_ack_frame()->set_sequence(sequence);
  return request(message, v1::ServerMessage::kFrameAcked).frame_acked();
}

void Client::ack_frame_async(std::uint64_t sequence) {
  v1::ClientMessage message;
  message.mutable_ack_frame()->set_sequence(sequence);
  send(message);
}

}  // namespace felt::client
