// felt hello, scenes, load, stats; and connecting, which every command does first.

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "wire/host_port.hpp"

namespace felt::cli {

namespace v1 = felt::v1;
using client::ClientError;

namespace {

wire::HostPort address_of(const Common& common) {
  const auto address = wire::parse_host_port(common.server);
  if (!address) throw UsageError("--server: " + address.error());
  return *address;
}

void print_bodies(const v1::SceneLoaded& scene) {
  std::printf("scene %llu \"%s\"%s%s, time step %g s\n",
              static_cast<unsigned long long>(scene.scene_id()), scene.name().c_str(),
              scene.shared() ? ", shared" : "", scene.paused() ? ", paused" : "",
              scene.time_step());
  for (const v1::BodyInfo& body : scene.bodies()) {
    std::printf("  body %u  %-8s %-16s %6u vertices %6u triangles  owner %u\n", body.body_id(),
                body.kind().c_str(), body.name().c_str(), body.particles(), body.triangles(),
                body.owner());
  }
}

}  // namespace

v1::Welcome connect(client::Client& client, const Common& common, const std::string& name) {
  const wire::HostPort address = address_of(common);
  client.connect(address.host, address.port);
  v1::Welcome welcome = client.hello(name, common.token);
  if (!common.scene.empty()) {
    Spinner waiting("loading " + common.scene);
    client.load_scene_by_name(common.scene);
  }
  if (common.join != 0) client.join_scene(common.join);
  return welcome;
}

v1::Welcome connect(client::AsyncClient& client, const Common& common, const std::string& name) {
  const wire::HostPort address = address_of(common);
  v1::Welcome welcome = client.connect(address.host, address.port, name, common.token);
  v1::ClientMessage message;
  if (!common.scene.empty()) {
    message.mutable_load_scene()->set_name(common.scene);
    Spinner waiting("loading " + common.scene);
    client.request(message);
  }
  if (common.join != 0) {
    message.mutable_join_scene()->set_scene_id(common.join);
    client.request(message);
  }
  return welcome;
}

int hello(const Common& common) {
  client::Client client;
  const v1::Welcome welcome = connect(client, common);
  std::printf("feltd %s, protocol %u, client %u, scene %llu\ncapabilities:",
              welcome.server_version().c_str(), welcome.protocol_version(), welcome.client_id(),
              static_cast<unsigned long long>(welcome.scene_id()));
  for (const std::string& capability : welcome.capabilities()) {
    std::printf(" %s", capability.c_str());
  }
  const v1::Limits& limits = welcome.limits();
  std::printf(
      "\nlimits: %u clients, %u scenes, %u bodies and %llu particles per scene, "
      "%u proxies, %u requests in flight, %g requests a second, frames up to %g Hz, messages up "
      "to %llu bytes\n",
      limits.max_clients(), limits.max_scenes(), limits.max_bodies_per_scene(),
      static_cast<unsigned long long>(limits.max_particles_per_scene()), limits.max_proxies(),
      limits.max_requests_in_flight(), limits.max_request_rate(), limits.max_frame_rate_hz(),
      static_cast<unsigned long long>(limits.max_frame_bytes()));
  return 0;
}

int list_scenes(const Common& common) {
  client::Client client;
  connect(client, common);
  const v1::SceneList list = client.list_scenes();
  std::printf("scene files:\n");
  for (const std::string& name : list.files()) std::printf("  %s\n", name.c_str());
  std::printf("running:\n");
  for (const v1::RunningScene& scene : list.running()) {
    std::printf("  %llu  %-20s %2u clients %3u bodies  t %.3f s%s%s%s\n",
                static_cast<unsigned long long>(scene.scene_id()), scene.name().c_str(),
                scene.clients(), scene.bodies(), scene.sim_time(), scene.shared() ? "  shared" : "",
                scene.paused() ? "  paused" : "", scene.persistent() ? "  kept" : "");
  }
  return 0;
}

int load(const Common& common, const LoadOptions& options) {
  client::Client client;
  connect(client, common);
  v1::ClientMessage message;
  v1::LoadScene& load = *message.mutable_load_scene();
  if (!options.json_file.empty()) {
    std::ifstream in(options.json_file);
    if (!in) throw UsageError("cannot read " + options.json_file);
    std::ostringstream text;
    text << in.rdbuf();
    load.set_json(text.str());
  } else {
    load.set_name(options.name);
  }
  load.set_shared(options.shared);
  // the scene outlives this command: others join it with --join
  load.set_keep(true);
  v1::ServerMessage loaded;
  {
    Spinner waiting("loading " + (options.name.empty() ? options.json_file : options.name));
    loaded = client.request(message, v1::ServerMessage::kSceneLoaded);
  }
  print_bodies(loaded.scene_loaded());
  return 0;
}

int stats(const Common& common) {
  client::Client client;
  connect(client, common);
  const v1::Stats stats = client.stats();
  if (stats.has_scene()) {
    const v1::SceneStats& s = stats.scene();
    std::printf("scene %llu: step %llu, t %.3f s, rtf %.2f, %.3f ms/step%s, time scale %g\n",
                static_cast<unsigned long long>(s.scene_id()),
                static_cast<unsigned long long>(s.steps()), s.sim_time(), s.real_time_factor(),
                s.ms_per_step(), s.paused() ? ", paused" : "", s.time_scale());
    std::printf(
        "  %u clients, %u bodies, %llu particles, %llu haptic updates, %llu rescued, "
        "%llu unrecoverable and %llu over-budget steps\n",
        s.clients(), s.bodies(), static_cast<unsigned long long>(s.particles()),
        static_cast<unsigned long long>(s.haptic_updates()),
        static_cast<unsigned long long>(s.rescued_steps()),
        static_cast<unsigned long long>(s.unrecoverable_steps()),
        static_cast<unsigned long long>(s.over_budget_steps()));
    // one line per body: "  body 0 cloth symplectic_euler: 2 substeps, 0 rescued, 0 over budget"
    // and ", max step 0.00025 s" when it has its own
    for (const v1::BodyStats& body : s.body_stats()) {
      std::printf("  body %u %s %s: %u substeps, %llu rescued, %llu over budget", body.body_id(),
                  body.kind().c_str(), body.integrator().c_str(), body.substeps(),
                  static_cast<unsigned long long>(body.rescued_steps()),
                  static_cast<unsigned long long>(body.over_budget_steps()));
      if (body.max_step() > 0) std::printf(", max step %g s", body.max_step());
      std::printf("\n");
    }
    // one line per system: "cloth ms/step: integration 0.412, stretch_limit 0.101, ..."
    std::string system;
    for (const v1::StageTime& stage : s.stages()) {
      if (stage.system() != system) {
        std::printf("%s  %s ms/step:", system.empty() ? "" : "\n", stage.system().c_str());
        system = stage.system();
      } else {
        std::printf(",");
      }
      std::printf(" %s %.3f", stage.stage().c_str(), stage.ms_per_step());
    }
    if (!system.empty()) std::printf("\n");
  } else {
    std::printf("no scene\n");
  }
  std::printf("server: %u clients, %u scenes, up %.1f s\n", stats.server().clients(),
              stats.server().scenes(), stats.server().uptime_s());
  return 0;
}

}  // namespace felt::cli
