// feltd: the Felt daemon (`serve`) and the headless batch runner (`run`).

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <thread>

#include <CLI/CLI.hpp>
#include <boost/asio.hpp>
#include <nlohmann/json.hpp>

#include "command_line/usage_status.hpp"
#include "net/endpoint_text.hpp"
#include "net/server.hpp"
#include "runtime/batch_run.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_overrides.hpp"
#include "scheduling/latency_options.hpp"
#include "scheduling/thread_name.hpp"
#include "wire/host_port.hpp"

namespace {

namespace asio = boost::asio;
using felt::SceneId;

struct ServeOptions {
  std::string listen = "127.0.0.1:7450";
  std::string web;                       ///< HOST:PORT of the page and its WebSocket; empty: off
  std::string web_root = FELT_WEB_ROOT;  ///< the page's build folder
  std::string scene_dir = "scenes";
  std::vector<std::string> scenes;
  /// who may pause, step, scale, reset, save and restore the --scene scenes: anyone, none
  std::string server_scenes_control = "anyone";
  bool status = false;
  std::string log_level = "info";
  unsigned io_threads = 2;
  int realtime_priority = 0;       ///< SCHED_FIFO priority of the network threads; 0: normal policy
  int network_slice_us = 100;      ///< time slice the network threads ask for; 0: the kernel's
  int cpu_wakeup_latency_us = -1;  ///< held while serving; 0: idle cores poll; -1: the system's
  int spin_idle_cores_ms = 0;      ///< idle cores spin this long after a haptic update; 0: never
  felt::net::ServerOptions limits;
};

struct RunOptions {
  std::string scene;
  std::string scene_dir;
  std::uint64_t steps = 0;
  std::vector<std::string> overrides;
  std::string stats_json;
  std::string record;
  std::string replay;
};

/// The network threads' requests of the scheduler, named as feltd's flags are.
const felt::LatencyNames kNetworkLatencyNames{"network threads", "--network-slice-us", "--realtime",
                                              "--cpu-wakeup-latency-us", "--spin-idle-cores-ms"};

felt::LatencyOptions latency_options(const ServeOptions& options) {
  felt::LatencyOptions latency;
  latency.slice = std::chrono::microseconds(options.network_slice_us);
  latency.realtime_priority = options.realtime_priority;
  if (options.cpu_wakeup_latency_us >= 0) {
    latency.cpu_wakeup_latency = std::chrono::microseconds(options.cpu_wakeup_latency_us);
  }
  latency.spin_idle_cores = std::chrono::milliseconds(options.spin_idle_cores_ms);
  return latency;
}

/// Mesh files of a scene resolve inside the scene directory, as they do for clients.
felt::SceneLoadOptions scene_options(const std::filesystem::path& scene_dir) {
  felt::SceneLoadOptions options;
  options.asset_root = scene_dir;
  return options;
}

/// Prints one status line a second for the first scene: what `scripts/run` shows.
void print_status(felt::SceneRegistry& scenes, SceneId scene, felt::net::Server& server,
                  std::uint64_t& last_haptic_updates) {
  const auto runner = scenes.find(scene);
  if (!runner) return;
  const felt::RunnerStats stats = runner->stats();
  std::printf("sim %9.3f s  rtf %5.2f  %7.3f ms/step  clients %zu  haptic %6llu/s\n",
              stats.sim_time, stats.real_time_factor, stats.ms_per_step, server.client_count(),
              static_cast<unsigned long long>(stats.haptic_updates - last_haptic_updates));
  std::fflush(stdout);
  last_haptic_updates = stats.haptic_updates;
}

int serve(const ServeOptions& options) {
  const auto address = felt::wire::parse_host_port(options.listen);
  if (!address) {
    std::cerr << "feltd: --listen: " << address.error() << "\n";
    return 2;
  }
  const auto web_address =
      options.web.empty() ? std::nullopt : std::optional(felt::wire::parse_host_port(options.web));
  if (web_address && !*web_address) {
    std::cerr << "feltd: --web: " << web_address->error() << "\n";
    return 2;
  }
  felt::SceneRegistry scenes;
  felt::net::ServerContext context{
      scenes, felt::SceneDirectory(options.scene_dir), options.limits, FELT_VERSION,
      felt::net::ServerLog(*felt::net::parse_log_level(options.log_level))};
  const felt::net::ServerLog& log = context.log;
  // named as feltd's other threads are (for top -H, perf and scripts/trace-round-trips); the
  // encoder steps aside for the network threads as the physics threads do. The loader does
  // not: a scene it starts gets its servo thread, which is on the haptic path, at the loader's
  // nice, and a thread cannot lower its nice again without privilege. Waited for, so that they
  // are set up when the server says it listens.
  asio::post(context.loader,
             asio::use_future([] { felt::name_thread(pthread_self(), "felt-loader"); }))
      .get();
  asio::post(context.frame_encoder, asio::use_future([nice = options.limits.background_nice] {
               felt::name_thread(pthread_self(), "felt-frames");
               // in range: the flag is checked
               if (nice != 0) (void)felt::set_this_thread_nice(nice);
             }))
      .get();
  for (const std::string& file : options.scenes) {
    auto document = felt::read_scene_json(file);
    auto scene = document ? felt::load_scene(*document, scene_options(options.scene_dir))
                          : std::unexpected(document.error());
    if (!scene) {
      std::cerr << "feltd: " << file << ": " << scene.error().what() << "\n";
      return 2;
    }
    // the server's own scenes are shared by everyone in them and stay while nobody is; the
    // operator says whether clients control them
    auto runner = std::make_shared<felt::SceneRunner>(
        std::move(*scene),
        felt::SceneAccess{0, true, true, options.server_scenes_control == "anyone"},
        [document = std::move(*document), load_options = scene_options(options.scene_dir)] {
          return felt::load_scene(document, load_options);
        },
        felt::SceneLimits{options.limits.max_bodies_per_scene,
                          options.limits.max_particles_per_scene});
    runner->start(options.limits.background_nice);
    const std::string name = runner->name();
    const SceneId id = scenes.add(std::move(runner));
    if (context.default_scene == 0) context.default_scene = id;
    log.info("scene " + std::to_string(id) + " \"" + name + "\" loaded from " + file +
             (id == context.default_scene ? ", the scene new clients join" : ""));
  }

  // the spinners start before the server listens, so that they are there for its first client
  felt::AppliedLatency latency = felt::apply(latency_options(options), kNetworkLatencyNames);
  context.idle_core_spinners = latency.spinners();
  felt::net::IoPool io(options.io_threads);
  felt::net::Server server(io, context);
  const auto endpoint = server.listen(address->host, address->port);
  if (!endpoint) {
    std::cerr << "feltd: " << endpoint.error() << "\n";
    scenes.stop_all();
    return 1;
  }
  std::printf("listening on %s\n", felt::net::endpoint_text(*endpoint).c_str());
  if (web_address) {
    const auto web =
        server.listen_web((*web_address)->host, (*web_address)->port, options.web_root);
    if (!web) {
      std::cerr << "feltd: --web: " << web.error() << "\n";
      scenes.stop_all();
      return 1;
    }
    std::printf("web on http://%s/\n", felt::net::endpoint_text(*web).c_str());
    if (!std::filesystem::exists(std::filesystem::path(options.web_root) / "index.html")) {
      log.warning("--web-root " + options.web_root + " has no index.html: build the page first");
    }
  }
  std::fflush(stdout);

  // the daemon's own timers and signals take turns on one strand; sessions have theirs
  const auto control = asio::make_strand(io.main());
  asio::steady_timer status_timer(control);
  std::uint64_t last_haptic_updates = 0;
  std::function<void()> schedule_status = [&] {
    status_timer.expires_after(std::chrono::seconds(1));
    status_timer.async_wait([&](const boost::system::error_code& ec) {
      if (ec) return;
      print_status(scenes, context.default_scene, server, last_haptic_updates);
      schedule_status();
    });
  };
  if (options.status) schedule_status();

  // SIGINT/SIGTERM: stop accepting, close the sessions, finish the current steps, exit 0
  asio::signal_set signals(control, SIGINT, SIGTERM);
  // on a signal: close the sessions on their strands, then stop once they are gone (or after
  // two seconds, so that a stuck session cannot keep the process alive)
  asio::steady_timer drain_timer(control);
  std::function<void(std::chrono::steady_clock::time_point)> drain =
      [&](std::chrono::steady_clock::time_point deadline) {
        if (server.client_count() == 0 || std::chrono::steady_clock::now() > deadline) {
          io.stop();
          return;
        }
        drain_timer.expires_after(std::chrono::milliseconds(10));
        drain_timer.async_wait([&, deadline](const boost::system::error_code& ec) {
          if (!ec) drain(deadline);
        });
      };
  signals.async_wait([&](const boost::system::error_code& ec, int signal) {
    if (ec) return;
    log.info(std::string("shutting down on ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") + ", " +
             std::to_string(server.client_count()) + " clients connected");
    status_timer.cancel();
    // each scene finishes its step, then every client hears that the server stops and its
    // connection closes once what is queued for it is written
    scenes.stop_all();
    server.shutdown();
    drain(std::chrono::steady_clock::now() + std::chrono::seconds(2));
  });
  // more than one thread runs the network, each its own connections, so that a client's haptic
  // update is answered while another thread builds a frame for others; with a short slice, or a
  // real-time policy, they answer as soon as an update arrives instead of waiting behind the
  // physics threads for a core (apply() scheduled this one)
  for (const std::string& note : latency.notes()) std::printf("%s\n", note.c_str());
  for (const std::string& error : latency.errors()) log.error(error);
  if (options.limits.background_nice != 0) {
    std::printf("physics and frame encoder: nice %d\n", options.limits.background_nice);
  }
  std::fflush(stdout);
  io.run([&latency] { latency.schedule_this_thread(); });
  // an orderly end: the scenes stop (cancelling what they had queued), the loader and the frame
  // encoder finish (a frame planned after this is never encoded: its session is closing), and
  // every session still open is closed and runs down while the io_contexts still run, so that
  // nothing is destroyed inside their destructors
  scenes.stop_all();
  context.loader.join();
  context.frame_encoder.join();
  server.close_all();
  io.run_down();
  log.info("stopped, exit status 0");
  return 0;
}

/// `profile`'s stages of `stages`, in milliseconds, by name.
nlohmann::json stage_ms_to_json(const felt::StepProfile& profile,
                                std::span<const felt::StepStage> stages) {
  nlohmann::json json = nlohmann::json::object();
  for (felt::StepStage stage : stages) json[felt::stage_name(stage)] = 1e3 * profile[stage];
  return json;
}

nlohmann::json stats_to_json(const felt::BatchRunStats& stats) {
  nlohmann::json bodies = nlohmann::json::array();
  // the scene's size the way the second thesis's Table 7.2 counts it: all solids together
  nlohmann::json solid_totals = {{"nodes", 0}, {"edges", 0},         {"triangles", 0},
                                 {"tets", 0},  {"fine_vertices", 0}, {"fine_triangles", 0}};
  for (const felt::BodyRunStats& body : stats.bodies) {
    nlohmann::json entry = {{"name", body.name},
                            {"kind", body.kind},
                            {"particles", body.particles},
                            {"edges", body.edges},
                            {"triangles", body.triangles},
                            {"tets", body.tets},
                            {"kinetic_energy", body.kinetic_energy}};
    if (body.kind == "cloth") {
      entry["max_strain"] = body.max_strain;
    } else {
      entry["fine_vertices"] = body.fine_vertices;
      entry["fine_triangles"] = body.fine_triangles;
      entry["volume_ratio"] = body.volume_ratio;
      for (const auto& [key, count] :
           {std::pair{"nodes", body.particles}, std::pair{"edges", body.edges},
            std::pair{"triangles", body.triangles}, std::pair{"tets", body.tets},
            std::pair{"fine_vertices", body.fine_vertices},
            std::pair{"fine_triangles", body.fine_triangles}}) {
        solid_totals[key] = solid_totals[key].get<std::size_t>() + count;
      }
    }
    bodies.push_back(std::move(entry));
  }
  const felt::SolidRunStats& solids = stats.solids;
  const felt::HapticRunStats& haptics = stats.haptics;
  return {{"steps", stats.steps},
          {"sim_time", stats.sim_time},
          {"wall_seconds", stats.wall_seconds},
          {"ms_per_step", stats.ms_per_step},
          {"nonfinite", stats.nonfinite},
          {"rescued_steps", stats.rescued_steps},
          {"unrecoverable_steps", stats.unrecoverable_steps},
          {"bodies", bodies},
          {"solids",
           {{"totals", solid_totals},
            {"mean_colliding_nodes", solids.mean_colliding_nodes},
            {"max_colliding_nodes", solids.max_colliding_nodes},
            {"mean_colliding_triangles", solids.mean_colliding_triangles},
            {"max_colliding_triangles", solids.max_colliding_triangles},
            {"max_substeps", solids.max_substeps},
            {"mean_stage_ms", stage_ms_to_json(solids.mean, felt::SolidSystem::kStages)},
            {"max_stage_ms", stage_ms_to_json(solids.max, felt::SolidSystem::kStages)}}},
          {"cloth",
           {{"max_substeps", stats.cloth.max_substeps},
            {"mean_stage_ms", stage_ms_to_json(stats.cloth.mean, felt::ClothSystem::kStages)},
            {"max_stage_ms", stage_ms_to_json(stats.cloth.max, felt::ClothSystem::kStages)}}},
          {"haptics",
           {{"ticks", haptics.ticks},
            {"contact_ticks", haptics.contact_ticks},
            {"mean_contact_us", haptics.mean_contact_us},
            {"mean_free_us", haptics.mean_free_us},
            {"max_force", haptics.max_force},
            {"max_force_step", haptics.max_force_step},
            {"mean_force_step", haptics.mean_force_step},
            {"compared", haptics.compared},
            {"equivalent", haptics.equivalent}}}};
}

int run(const RunOptions& options) {
  auto document = felt::read_scene_json(options.scene);
  if (!document) {
    std::cerr << "feltd: " << document.error().what() << "\n";
    return 2;
  }
  for (const std::string& assignment : options.overrides) {
    if (auto applied = felt::apply_override(*document, assignment); !applied) {
      std::cerr << "feltd: --set " << assignment << ": " << applied.error() << "\n";
      return 2;
    }
  }
  // without --scene-dir, meshes are looked up beside the scene file
  const std::filesystem::path beside = std::filesystem::path(options.scene).parent_path();
  auto scene = felt::load_scene(
      *document, scene_options(!options.scene_dir.empty() ? std::filesystem::path(options.scene_dir)
                               : beside.empty()           ? std::filesystem::path(".")
                                                          : beside));
  if (!scene) {
    std::cerr << "feltd: " << options.scene << ": " << scene.error().what() << "\n";
    return 2;
  }
  felt::BatchHaptics haptics;
  std::vector<felt::HapticRecord> replayed;
  if (!options.replay.empty()) {
    std::ifstream in(options.replay);
    auto records =
        in ? felt::read_recording(in) : std::unexpected(std::string("cannot open the file"));
    if (!records) {
      std::cerr << "feltd: --replay " << options.replay << ": " << records.error() << "\n";
      return 2;
    }
    replayed = std::move(*records);
    haptics.replay = &replayed;
  }
  std::ofstream recording;
  if (!options.record.empty()) {
    recording.open(options.record);
    if (!recording) {
      std::cerr << "feltd: --record: cannot write " << options.record << "\n";
      return 2;
    }
    haptics.record = &recording;
  }
  const felt::BatchRunStats stats = felt::run_batch(*scene, options.steps, haptics);
  const nlohmann::json json = stats_to_json(stats);
  std::printf("%llu steps, sim %.4f s, wall %.3f s, %.4f ms/step\n",
              static_cast<unsigned long long>(stats.steps), stats.sim_time, stats.wall_seconds,
              stats.ms_per_step);
  if (const auto& totals = json["solids"]["totals"]; totals["nodes"].get<std::size_t>() > 0) {
    std::printf("solids: %zu nodes, %zu edges, %zu triangles, %zu tetrahedra\n",
                totals["nodes"].get<std::size_t>(), totals["edges"].get<std::size_t>(),
                totals["triangles"].get<std::size_t>(), totals["tets"].get<std::size_t>());
  }
  if (const felt::HapticRunStats& h = stats.haptics; h.ticks > 0) {
    std::printf(
        "haptics: %llu ticks, %llu in contact, %.2f us/tick in contact, %.2f free, "
        "max force %.3f N, force step max %.4f N mean %.5f N\n",
        static_cast<unsigned long long>(h.ticks), static_cast<unsigned long long>(h.contact_ticks),
        h.mean_contact_us, h.mean_free_us, h.max_force, h.max_force_step, h.mean_force_step);
    if (h.compared > 0) {
      std::printf("replay: %llu of %llu updates collision-equivalent to the recording\n",
                  static_cast<unsigned long long>(h.equivalent),
                  static_cast<unsigned long long>(h.compared));
    }
  }
  if (stats.nonfinite) {
    std::printf("UNSTABLE: %llu steps could not be rescued (rolled back, body stopped)\n",
                static_cast<unsigned long long>(stats.unrecoverable_steps));
  }
  if (!options.stats_json.empty()) {
    std::ofstream out(options.stats_json);
    out << json.dump(2) << "\n";
    if (!out) {
      std::cerr << "feltd: cannot write " << options.stats_json << "\n";
      return 1;
    }
  }
  return stats.nonfinite ? 3 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"feltd " FELT_VERSION " - simulation service for touching deformable things"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "feltd " FELT_VERSION);

  ServeOptions serve_options;
  felt::net::ServerOptions& limits = serve_options.limits;
  if (const char* token = std::getenv("FELT_TOKEN")) limits.token = token;
  CLI::App* serve_cmd =
      app.add_subcommand("serve", "Serve scenes over TCP and WebSocket (protocol felt.v1)");
  serve_cmd
      ->add_option("--listen", serve_options.listen, "HOST:PORT to listen on; port 0 picks one")
      ->capture_default_str();
  serve_cmd->add_option("--web", serve_options.web,
                        "HOST:PORT to serve the page and its WebSocket (/ws) on; port 0 picks one "
                        "(default: off)");
  serve_cmd->add_option("--web-root", serve_options.web_root, "The page's build folder")
      ->capture_default_str();
  serve_cmd
      ->add_option("--scene-dir", serve_options.scene_dir,
                   "Directory clients load scenes from by name")
      ->capture_default_str();
  serve_cmd
      ->add_option("--scene", serve_options.scenes,
                   "Scene file to load at start; the first is the one new clients join")
      ->check(CLI::ExistingFile);
  serve_cmd
      ->add_option("--server-scenes-control", serve_options.server_scenes_control,
                   "Who may pause, step, scale, reset, save and restore the --scene scenes: "
                   "anyone in them, or none (clients still watch, touch and change bodies)")
      ->check(CLI::IsMember({"anyone", "none"}))
      ->capture_default_str();
  serve_cmd->add_flag("--status", serve_options.status, "Print a status line every second");
  serve_cmd
      ->add_option("--log-level", serve_options.log_level,
                   "What to log on standard error, one line each: off, error, warning (refusals "
                   "of a limit), info (clients, scenes, shutdown) or debug (connections)")
      ->check(CLI::IsMember({"off", "error", "warning", "info", "debug"}))
      ->capture_default_str();
  serve_cmd
      ->add_option("--io-threads", serve_options.io_threads,
                   "Threads that run the network (each client's requests stay in order)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  serve_cmd
      ->add_option("--realtime", serve_options.realtime_priority,
                   "Run the network threads under SCHED_FIFO at this priority (1-99; 0: off) "
                   "so that haptic updates are answered at once on a busy machine")
      ->check(CLI::Range(0, felt::kMaxRealtimePriority))
      ->capture_default_str();
  serve_cmd
      ->add_option("--network-slice-us", serve_options.network_slice_us,
                   "Time slice the network threads ask the kernel for (Linux 6.12+), so that a "
                   "haptic update preempts a busy physics thread at once (0: the kernel's)")
      ->check(CLI::Range(0, 0) | CLI::Range(static_cast<int>(felt::kMinTimeSlice.count()),
                                            static_cast<int>(felt::kMaxTimeSlice.count())))
      ->capture_default_str();
  serve_cmd
      ->add_option("--background-nice", limits.background_nice,
                   "Nice of the busy threads off the haptic path: every scene's physics and the "
                   "frame encoder (0-19; no privilege), so that a haptic update's "
                   "network thread preempts them at once (0: as the network threads)")
      ->check(CLI::Range(0, felt::kMaxNice))
      ->capture_default_str();
  serve_cmd
      ->add_option("--cpu-wakeup-latency-us", serve_options.cpu_wakeup_latency_us,
                   "Hold every idle core's wake-up latency at most this (system-wide, root; 0: "
                   "idle cores poll, so an update wakes the network at once; -1: the system's)")
      ->check(CLI::Range(-1, static_cast<int>(felt::kMaxCpuWakeupLatency.count())))
      ->capture_default_str();
  serve_cmd
      ->add_option("--spin-idle-cores-ms", serve_options.spin_idle_cores_ms,
                   "Keep idle cores awake this long after each haptic update, with a spinning "
                   "thread per core that yields to any other (no privilege; 0: let them halt; "
                   "helps one device's median, docs/results/idle_core_spinners.md)")
      ->check(CLI::Range(0, 60'000))
      ->capture_default_str();
  serve_cmd->add_option("--token", limits.token,
                        "Shared secret every Hello must carry (default: $FELT_TOKEN)");
  serve_cmd
      ->add_option("--hello-timeout-ms", limits.hello_timeout_ms,
                   "A connection that has not said Hello (with the token) by then is closed, so "
                   "that silent connections cannot hold every --max-clients slot")
      ->check(CLI::Range(100, 3'600'000))
      ->capture_default_str();
  serve_cmd->add_option("--max-clients", limits.max_clients, "Connections served at once")
      ->check(CLI::Range(1, 100'000))
      ->capture_default_str();
  serve_cmd->add_option("--max-scenes", limits.max_scenes, "Scenes running at once")
      ->check(CLI::Range(1, 10'000))
      ->capture_default_str();
  serve_cmd
      ->add_option("--max-kept-scenes", limits.max_kept_scenes_per_client,
                   "Scenes one client loads with keep (they outlive it) that run at once")
      ->check(CLI::Range(0, 10'000))
      ->capture_default_str();
  serve_cmd->add_option("--max-bodies", limits.max_bodies_per_scene, "Bodies per scene")
      ->check(CLI::Range(1, 65'000))
      ->capture_default_str();
  serve_cmd
      ->add_option("--max-particles", limits.max_particles_per_scene,
                   "Particles per scene a client loads or builds")
      // as many as the server's own scene files may have; a frame of them stays within the
      // 256 MiB a client's decoder takes
      ->check(CLI::Range(1, 4'000'000))
      ->capture_default_str();
  serve_cmd->add_option("--max-proxies", limits.max_proxies_per_session, "Open proxies per client")
      ->check(CLI::Range(1, 10'000))
      ->capture_default_str();
  serve_cmd
      ->add_option("--max-requests-in-flight", limits.max_requests_in_flight,
                   "Requests per client still being worked on (loads, steps, saves)")
      ->check(CLI::Range(1, 10'000))
      ->capture_default_str();
  serve_cmd
      ->add_option("--max-frame-bytes", limits.max_inbound_frame_bytes,
                   "Largest message a client may send, in bytes")
      ->check(CLI::Range(1024, 1 << 30))
      ->capture_default_str();
  serve_cmd
      ->add_option("--max-reply-backlog", limits.max_queued_reply_bytes,
                   "Unread reply bytes after which a client is disconnected")
      ->check(CLI::Range(64 * 1024, 1 << 30))
      ->capture_default_str();
  serve_cmd
      ->add_option("--max-frame-rate", limits.max_frame_rate_hz,
                   "Highest frame rate a subscription may ask for, per second (a higher one is "
                   "refused)")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();

  RunOptions run_options;
  CLI::App* run_cmd = app.add_subcommand("run", "Step a scene headless, without a network");
  run_cmd->add_option("scene", run_options.scene, "Scene JSON file")
      ->required()
      ->check(CLI::ExistingFile);
  run_cmd->add_option("--steps", run_options.steps, "Number of steps")
      ->required()
      ->check(CLI::PositiveNumber);
  run_cmd->add_option(
      "--set", run_options.overrides,
      "KEY=VALUE override, KEY a dotted path (bodies.0.integrator), VALUE JSON or a string");
  run_cmd->add_option("--scene-dir", run_options.scene_dir,
                      "Directory mesh files resolve in (default: the scene file's directory)");
  run_cmd->add_option("--stats-json", run_options.stats_json, "Write run statistics to this file");
  run_cmd->add_option("--record", run_options.record,
                      "Write every scripted-device update (position, contact, force) to this CSV");
  run_cmd
      ->add_option("--replay", run_options.replay,
                   "Drive the devices from a --record CSV and compare their contacts with it")
      ->check(CLI::ExistingFile);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return felt::usage_status(app, e);
  }
  if (serve_cmd->parsed()) return serve(serve_options);
  return run(run_options);
}
