#include "net/dispatcher.hpp"

#include <chrono>
#include <cmath>

#include "runtime/scene_runner.hpp"
#include "scene/scene_loader.hpp"

namespace felt::net {
namespace {

namespace v1 = felt::v1;
using v1::ClientMessage;
using v1::ServerMessage;

std::uint64_t steady_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::steady_clock::now().time_since_epoch())
                                        .count());
}

void put_vec3(const Vec3& v, v1::Vec3& out) {
  out.set_x(v.x());
  out.set_y(v.y());
  out.set_z(v.z());
}

// Compares without an early exit, so the time taken does not reveal how much of a guess was
// right.
bool tokens_equal(const std::string& expected, const std::string& given) {
  unsigned char diff = expected.size() == given.size() ? 0 : 1;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    diff |= static_cast<unsigned char>(expected[i] ^ (i < given.size() ? given[i] : 0));
  }
  return diff == 0;
}

void handle_hello(Session& session, std::uint64_t request_id, const v1::Hello& hello) {
  const ServerContext& context = session.context();
  if (hello.protocol_version() != kProtocolVersion) {
    session.send_error(request_id, v1::ERROR_CODE_UNSUPPORTED_VERSION,
                       "this server speaks protocol version " + std::to_string(kProtocolVersion) +
                           ", not " + std::to_string(hello.protocol_version()));
    return;
  }
  if (!context.options.token.empty() && !tokens_equal(context.options.token, hello.token())) {
    session.send_error(request_id, v1::ERROR_CODE_UNAUTHORIZED, "wrong or missing token");
    return;
  }
  session.set_greeted();
  ServerMessage reply;
  reply.set_request_id(request_id);
  v1::Welcome* welcome = reply.mutable_welcome();
  welcome->set_protocol_version(kProtocolVersion);
  welcome->set_server_version(context.server_version);
  for (const char* capability :
       {"scenes.load", "frames.float32", "haptics.proxy", "bodies.set", "bodies.pin"}) {
    welcome->add_capabilities(capability);
  }
  welcome->set_scene_id(session.scene_id());
  session.send(reply);
}

void handle_load_scene(Session& session, std::uint64_t request_id, const v1::LoadScene& load) {
  ServerContext& context = session.context();
  if (context.scenes.size() >= context.options.max_scenes) {
    session.send_error(
        request_id, v1::ERROR_CODE_LIMIT_EXCEEDED,
        "the server already runs " + std::to_string(context.options.max_scenes) + " scenes");
    return;
  }
  SceneLoadOptions options;
  options.max_particles = context.options.max_particles_per_scene;
  options.asset_root = context.scene_directory.root();
  std::expected<Scene, SceneError> scene = std::unexpected(SceneError{"", "no scene given"});
  switch (load.source_case()) {
    case v1::LoadScene::kName: {
      const auto file = context.scene_directory.resolve(load.name());
      if (!file) {
        session.send_error(request_id, v1::ERROR_CODE_NOT_FOUND, file.error());
        return;
      }
      scene = load_scene_file(*file, options);
      if (!scene) {
        // the client named the scene; it has no business learning the server's paths
        SceneError& error = scene.error();
        for (std::size_t at; (at = error.message.find(file->string())) != std::string::npos;) {
          error.message.replace(at, file->string().size(), "scene \"" + load.name() + "\"");
        }
      }
      break;
    }
    case v1::LoadScene::kJson:
      scene = load_scene_text(load.json(), options);
      break;
    case v1::LoadScene::SOURCE_NOT_SET:
      session.send_error(request_id, v1::ERROR_CODE_BAD_REQUEST, "LoadScene needs a name or json");
      return;
  }
  if (!scene) {
    session.send_error(request_id, v1::ERROR_CODE_BAD_SCENE, scene.error().what());
    return;
  }
  auto runner = std::make_shared<SceneRunner>(std::move(*scene));
  runner->start();
  const SceneId id = context.scenes.add(runner);
  session.join(id, runner);

  ServerMessage reply;
  reply.set_request_id(request_id);
  v1::SceneLoaded* loaded = reply.mutable_scene_loaded();
  loaded->set_scene_id(id);
  loaded->set_name(runner->name());
  for (const BodyInfo& body : runner->bodies()) {
    v1::BodyInfo* info = loaded->add_bodies();
    info->set_body_id(body.body_id);
    info->set_name(body.name);
    info->set_kind(body.kind);
    info->set_particles(body.particles);
    info->set_triangles(body.triangles);
  }
  session.send(reply);
}

void handle_subscribe(Session& session, std::uint64_t request_id, const v1::SubscribeFrames& sub) {
  const ServerOptions& options = session.context().options;
  const double asked = sub.max_rate_hz();
  // a tiny rate would overflow the timer period; 0 asks for the default
  if (!std::isfinite(asked) || asked < 0 || (asked > 0 && asked < options.min_frame_rate_hz)) {
    session.send_error(request_id, v1::ERROR_CODE_BAD_REQUEST,
                       "max_rate_hz must be 0 (the default) or at least " +
                           std::to_string(options.min_frame_rate_hz));
    return;
  }
  const double rate = sub.max_rate_hz() == 0
                          ? options.default_frame_rate_hz
                          : std::min(sub.max_rate_hz(), options.max_frame_rate_hz);
  session.subscribe_frames(rate, sub.normals());
  ServerMessage reply;
  reply.set_request_id(request_id);
  reply.mutable_subscribed()->set_scene_id(session.scene_id());
  reply.mutable_subscribed()->set_rate_hz(rate);
  session.send(reply);
}

void handle_proxy_update(Session& session, std::uint64_t request_id,
                         const v1::ProxyUpdate& update) {
  const std::uint64_t received = steady_ns();
  const Vec3 position(update.position().x(), update.position().y(), update.position().z());
  if (!update.has_position() || !position.allFinite()) {
    session.send_error(request_id, v1::ERROR_CODE_BAD_REQUEST,
                       "position must be three finite numbers");
    return;
  }
  HapticProxy* proxy = session.open_proxy(update.proxy_id());
  if (!proxy) {
    session.send_error(request_id, v1::ERROR_CODE_LIMIT_EXCEEDED,
                       "at most " +
                           std::to_string(session.context().options.max_proxies_per_session) +
                           " proxies per session");
    return;
  }
  const ProxyOutput out = session.scene()->render(*proxy, position, update.buttons());
  const HapticContact& contact = out.contact;

  ServerMessage reply;
  reply.set_request_id(request_id);
  v1::ForceUpdate* force = reply.mutable_force_update();
  force->set_proxy_id(update.proxy_id());
  put_vec3(contact.force, *force->mutable_force());
  put_vec3(contact.contact_point, *force->mutable_contact_point());
  force->set_in_contact(contact.in_contact);
  force->set_body_id(out.grabbing ? out.grabbed_body : contact.body_id);
  force->set_triangle(contact.triangle);
  put_vec3(contact.proxy, *force->mutable_proxy());
  put_vec3(contact.normal, *force->mutable_normal());
  force->set_constraints(static_cast<std::uint32_t>(contact.constraints));
  force->set_slipping(contact.slipping);
  force->set_grabbing(out.grabbing);
  force->set_grabbed_vertex(out.grabbed_vertex);
  force->set_client_time_us(update.client_time_us());
  force->set_server_receive_ns(received);
  force->set_server_send_ns(steady_ns());
  session.send(reply);
}

void reply_body_updated(Session& session, std::uint64_t request_id, std::uint32_t body_id) {
  ServerMessage reply;
  reply.set_request_id(request_id);
  reply.mutable_body_updated()->set_body_id(body_id);
  session.send(reply);
}

/// True when `body_id` names a cloth of the session's scene; answers with an error otherwise.
bool known_cloth(Session& session, std::uint64_t request_id, std::uint32_t body_id) {
  const auto& bodies = session.scene()->bodies();
  if (body_id >= bodies.size()) {
    session.send_error(request_id, v1::ERROR_CODE_UNKNOWN_ID,
                       "no body " + std::to_string(body_id) + " in this scene");
    return false;
  }
  if (bodies[body_id].kind != "cloth") {
    session.send_error(request_id, v1::ERROR_CODE_BAD_REQUEST,
                       "body " + std::to_string(body_id) + " is a " + bodies[body_id].kind +
                           "; this request changes cloths only");
    return false;
  }
  return true;
}

void handle_set_body_parameters(Session& session, std::uint64_t request_id,
                                const v1::SetBodyParameters& set) {
  if (!known_cloth(session, request_id, set.body_id())) return;
  // everything is checked here, so the command applied by the physics thread cannot fail
  const auto bad = [&](const std::string& what) {
    session.send_error(request_id, v1::ERROR_CODE_BAD_REQUEST, what);
  };
  if (set.has_integrator() && !make_integrator(set.integrator())) {
    return bad("unknown integrator \"" + set.integrator() + "\"");
  }
  if (set.has_drag() && !(set.drag() >= 0 && std::isfinite(set.drag()))) {
    return bad("drag must be a finite number >= 0");
  }
  const std::pair<bool, double> stiffnesses[] = {
      {set.has_structural_stiffness(), set.structural_stiffness()},
      {set.has_shear_stiffness(), set.shear_stiffness()},
      {set.has_bend_stiffness(), set.bend_stiffness()}};
  for (const auto& [given, k] : stiffnesses) {
    if (given && !(k > 0 && std::isfinite(k))) return bad("stiffness must be a finite number > 0");
  }
  if (set.has_max_strain() && !(set.max_strain() >= 0 && std::isfinite(set.max_strain()))) {
    return bad("max_strain must be a finite number >= 0");
  }
  session.scene()->post([set](Scene& scene) {
    ClothBody& body = *scene.world.cloth(set.body_id());
    ClothParams params = body.params();
    if (set.has_drag()) params.drag = set.drag();
    if (set.has_structural_stiffness()) {
      params.spring(SpringKind::kStructural).stiffness = set.structural_stiffness();
    }
    if (set.has_shear_stiffness())
      params.spring(SpringKind::kShear).stiffness = set.shear_stiffness();
    if (set.has_bend_stiffness()) params.spring(SpringKind::kBend).stiffness = set.bend_stiffness();
    if (set.has_max_strain()) {
      params.stretch.enabled = set.max_strain() > 0;
      if (params.stretch.enabled) params.stretch.max_strain = set.max_strain();
    }
    body.set_params(params);
    if (set.has_integrator()) body.set_integrator(make_integrator(set.integrator()));
  });
  reply_body_updated(session, request_id, set.body_id());
}

void handle_pin_particles(Session& session, std::uint64_t request_id,
                          const v1::PinParticles& pins) {
  if (!known_cloth(session, request_id, pins.body_id())) return;
  const std::uint32_t particles = session.scene()->bodies()[pins.body_id()].particles;
  for (const auto* list : {&pins.pin(), &pins.unpin()}) {
    for (std::uint32_t p : *list) {
      if (p >= particles) {
        session.send_error(request_id, v1::ERROR_CODE_BAD_REQUEST,
                           "particle " + std::to_string(p) + " out of range (the body has " +
                               std::to_string(particles) + ")");
        return;
      }
    }
  }
  session.scene()->post([pins](Scene& scene) {
    ClothBody& body = *scene.world.cloth(pins.body_id());
    for (std::uint32_t p : pins.unpin()) body.unpin(p);
    for (std::uint32_t p : pins.pin()) body.pin(p);
  });
  reply_body_updated(session, request_id, pins.body_id());
}

}  // namespace

void dispatch(Session& session, const ClientMessage& message) {
  const std::uint64_t request_id = message.request_id();
  if (message.body_case() == ClientMessage::kHello) {
    handle_hello(session, request_id, message.hello());
    return;
  }
  if (!session.greeted()) {
    session.send_error(request_id, v1::ERROR_CODE_HELLO_REQUIRED, "send Hello first");
    return;
  }
  switch (message.body_case()) {
    case ClientMessage::kLoadScene:
      handle_load_scene(session, request_id, message.load_scene());
      return;
    case ClientMessage::kSubscribeFrames:
      if (!session.scene()) break;
      handle_subscribe(session, request_id, message.subscribe_frames());
      return;
    case ClientMessage::kProxyUpdate:
      if (!session.scene()) break;
      handle_proxy_update(session, request_id, message.proxy_update());
      return;
    case ClientMessage::kSetBodyParameters:
      if (!session.scene()) break;
      handle_set_body_parameters(session, request_id, message.set_body_parameters());
      return;
    case ClientMessage::kPinParticles:
      if (!session.scene()) break;
      handle_pin_particles(session, request_id, message.pin_particles());
      return;
    default:
      session.send_error(request_id, v1::ERROR_CODE_UNKNOWN_MESSAGE,
                         "a ClientMessage with no body this server knows");
      return;
  }
  session.send_error(request_id, v1::ERROR_CODE_NO_SCENE, "load or join a scene first");
}

}  // namespace felt::net
