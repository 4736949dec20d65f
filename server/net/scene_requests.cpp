// Scenes: list, load, create, join, leave, destroy.

#include <nlohmann/json.hpp>

#include "net/requests.hpp"
#include "scene/scene_loader.hpp"

namespace felt::net {
namespace {

using nlohmann::json;
/// Why a scene's document could not be had: a name that is not found, or a file that is not JSON.
struct ReadError {
  v1::ErrorCode code = v1::ERROR_CODE_BAD_SCENE;
  std::string message;
};
using DocumentSource = std::function<std::expected<json, ReadError>()>;

/// Why the server cannot start another scene for `client`, if it cannot.
std::optional<std::string> no_room(const ServerContext& context, ClientId client, bool keep) {
  if (context.scenes.size() >= context.options.max_scenes) {
    return "the server already runs " + std::to_string(context.options.max_scenes) +
           " scenes (--max-scenes)";
  }
  if (keep && context.scenes.kept_by(client) >= context.options.max_kept_scenes_per_client) {
    return "this client already keeps " +
           std::to_string(context.options.max_kept_scenes_per_client) +
           " scenes running (--max-kept-scenes); destroy one first";
  }
  return std::nullopt;
}

/// Reads and builds the scene `read` gives on the loader thread, starts it and joins the
/// session to it; the reply is SceneLoaded or the error.
void start_scene(Session& session, std::uint64_t id, DocumentSource read, bool shared, bool keep) {
  ServerContext& context = session.context();
  const ClientId client = session.client_id();
  if (const auto full = no_room(context, client, keep)) {
    session.send_error(id, v1::ERROR_CODE_LIMIT_EXCEEDED, *full);
    return;
  }
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  std::weak_ptr<Session> weak = session.weak_from_this();
  boost::asio::post(context.loader, [&context, pending, weak, client, read = std::move(read),
                                     shared, keep] {
    SceneLoadOptions options;
    options.max_particles = context.options.max_particles_per_scene;
    options.asset_root = context.scene_directory.root();
    auto document = read();
    if (!document) {
      pending->fail(document.error().code, document.error().message);
      return;
    }
    auto scene = load_scene(*document, options);
    if (!scene) {
      fail(*pending, load_error(scene.error()));
      return;
    }
    if (scene->world.body_count() > context.options.max_bodies_per_scene) {
      fail(*pending,
           {RunnerError::Code::kLimitExceeded,
            "the scene has " + std::to_string(scene->world.body_count()) +
                " bodies; a scene may have " + std::to_string(context.options.max_bodies_per_scene),
            SceneLimit::kBodies});
      return;
    }
    if (const auto full = no_room(context, client, keep)) {  // others may have loaded since
      pending->fail(v1::ERROR_CODE_LIMIT_EXCEEDED, *full);
      return;
    }
    auto runner = std::make_shared<SceneRunner>(
        std::move(*scene), SceneAccess{client, shared, keep},
        [document = std::move(*document), options] { return load_scene(document, options); },
        SceneLimits{context.options.max_bodies_per_scene, context.options.max_particles_per_scene});
    runner->start(context.options.background_nice);
    // the loading client is in it from the start, so that it is nobody else's meanwhile
    const SceneId scene_id = context.scenes.add(runner, SceneMembers::Member{client, {}, {}});
    auto session = weak.lock();
    if (!session) {
      context.scenes.leave(scene_id, client);  // nobody is in it: it goes again
      return;
    }
    session->post([session, scene_id, runner, pending, &context, client] {
      if (session->closed() || !session->join(scene_id)) {
        context.scenes.leave(scene_id, client);  // nobody will be in it: it goes again
        pending->fail(v1::ERROR_CODE_CANCELLED, "the scene stopped before it could be joined");
        return;
      }
      context.log.info(session->who() + " loaded scene " + std::to_string(scene_id.value()) +
                       " \"" + runner->name() + "\"" + (runner->access().shared ? ", shared" : "") +
                       (runner->access().persistent ? ", kept" : ""));
      v1::ServerMessage message;
      fill_scene_loaded(scene_id, *runner, *message.mutable_scene_loaded());
      pending->send(std::move(message));
    });
  });
}

}  // namespace

Offload on_loader(ServerContext& context, std::shared_ptr<SceneRunner> scene) {
  return [&context, scene = std::move(scene)](std::function<void()> job) {
    boost::asio::post(context.loader, [scene, job = std::move(job)] { job(); });
  };
}

void fill_scene_loaded(SceneId scene_id, const SceneRunner& scene, v1::SceneLoaded& out) {
  out.set_scene_id(scene_id.value());
  out.set_name(scene.name());
  for (const BodyInfo& body : scene.bodies()->bodies) fill_body_info(body, *out.add_bodies());
  out.set_shared(scene.access().shared);
  out.set_paused(scene.stats().paused);
  out.set_time_step(scene.time_step());
  out.set_owner(scene.access().owner.value());
}

void handle_list_scenes(Session& session, std::uint64_t id) {
  // read on the loader thread and counted by --max-requests-in-flight, as loads are: a listing
  // reads the scene directory, and a client sending them by the thousand would otherwise hold
  // a network thread and everyone on it
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  ServerContext& context = session.context();
  boost::asio::post(context.loader, [&context, pending] {
    v1::ServerMessage message;
    v1::SceneList& list = *message.mutable_scene_list();
    for (std::string& name : context.scene_directory.list()) list.add_files(std::move(name));
    for (const auto& [scene_id, runner] : context.scenes.list()) {
      v1::RunningScene& running = *list.add_running();
      const RunnerStats stats = runner->stats();
      running.set_scene_id(scene_id.value());
      running.set_name(runner->name());
      running.set_clients(static_cast<std::uint32_t>(runner->members().count()));
      running.set_bodies(static_cast<std::uint32_t>(runner->bodies()->bodies.size()));
      running.set_shared(runner->access().shared);
      running.set_paused(stats.paused);
      running.set_sim_time(stats.sim_time);
      running.set_persistent(runner->access().persistent);
    }
    pending->send(std::move(message));
  });
}

void handle_load_scene(Session& session, std::uint64_t id, const v1::LoadScene& load) {
  const ServerContext& context = session.context();
  switch (load.source_case()) {
    case v1::LoadScene::kName:
      start_scene(
          session, id,
          [&context, name = load.name()]() -> std::expected<json, ReadError> {
            const auto file = context.scene_directory.resolve(name);
            if (!file) return std::unexpected(ReadError{v1::ERROR_CODE_NOT_FOUND, file.error()});
            auto document = read_scene_json(*file);
            if (document) return std::move(*document);
            // the client named the scene; it has no business learning the server's paths
            std::string message = document.error().what();
            const std::string path = file->string();
            for (std::size_t at; (at = message.find(path)) != std::string::npos;) {
              message.replace(at, path.size(), "scene \"" + name + "\"");
            }
            return std::unexpected(ReadError{v1::ERROR_CODE_BAD_SCENE, std::move(message)});
          },
          load.shared(), load.keep());
      return;
    case v1::LoadScene::kJson:
      start_scene(
          session, id,
          [text = load.json()]() -> std::expected<json, ReadError> {
            auto document = parse_json(text, "the scene");
            if (document) return std::move(*document);
            return std::unexpected(ReadError{v1::ERROR_CODE_BAD_SCENE, document.error().what()});
          },
          load.shared(), load.keep());
      return;
    case v1::LoadScene::SOURCE_NOT_SET:
      session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, "LoadScene needs a name or json");
      return;
  }
}

void handle_create_scene(Session& session, std::uint64_t id, const v1::CreateScene& create) {
  json document = {{"name", create.name().empty() ? "unnamed" : create.name()}};
  if (create.has_time_step()) document["time_step"] = create.time_step();
  if (create.has_gravity()) {
    document["gravity"] = {create.gravity().x(), create.gravity().y(), create.gravity().z()};
  }
  // the scene loader checks every value as it checks a file's
  start_scene(
      session, id, [document]() -> std::expected<json, ReadError> { return document; },
      create.shared(), create.keep());
}

void handle_join_scene(Session& session, std::uint64_t id, const v1::JoinScene& join) {
  const bool already_there = session.scene() && join.scene_id() == session.scene_id();
  if (!already_there && !session.join(join.scene_id())) {
    session.send_error(id, v1::ERROR_CODE_UNKNOWN_ID,
                       "no scene " + std::to_string(join.scene_id()));
    return;
  }
  reply(session, id, [&](v1::ServerMessage& message) {
    fill_scene_loaded(session.scene_id(), *session.scene(), *message.mutable_scene_loaded());
  });
}

void handle_leave_scene(Session& session, std::uint64_t id) {
  const SceneId left = session.scene_id();
  session.leave_scene();
  reply(session, id, [&](v1::ServerMessage& message) {
    message.mutable_scene_left()->set_scene_id(left.value());
  });
}

void handle_destroy_scene(Session& session, std::uint64_t id, const v1::DestroyScene& destroy) {
  ServerContext& context = session.context();
  const SceneId scene_id = destroy.scene_id() != 0 ? destroy.scene_id() : session.scene_id();
  if (scene_id == 0) {
    session.send_error(id, v1::ERROR_CODE_NO_SCENE, "name a scene or join one");
    return;
  }
  const auto scene = context.scenes.find(scene_id);
  if (!scene) {
    session.send_error(id, v1::ERROR_CODE_UNKNOWN_ID,
                       "no scene " + std::to_string(scene_id.value()));
    return;
  }
  if (scene->access().owner == 0) {
    session.send_error(id, v1::ERROR_CODE_PERMISSION_DENIED,
                       "the server's own scenes cannot be destroyed");
    return;
  }
  if (!scene->may_control(session.client_id())) {
    session.send_error(id, v1::ERROR_CODE_PERMISSION_DENIED,
                       "only the client that loaded the scene may destroy it (it is not shared)");
    return;
  }
  SceneEvent destroyed;
  destroyed.kind = SceneEvent::Kind::kDestroyed;
  destroyed.client = session.client_id();
  scene->members().broadcast_to_all(std::move(destroyed));
  if (session.scene_id() == scene_id) session.leave_scene();
  context.scenes.remove(scene_id);
  context.log.info(session.who() + " destroyed scene " + std::to_string(scene_id.value()) + " \"" +
                   scene->name() + "\"");
  reply(session, id, [&](v1::ServerMessage& message) {
    message.mutable_scene_destroyed()->set_scene_id(scene_id.value());
  });
}

}  // namespace felt::net
