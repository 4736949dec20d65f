#include "feltd/serve_command.hpp"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include <boost/asio.hpp>
#include <nlohmann/json.hpp>

#include "feltd/scene_options.hpp"
#include "net/endpoint_text.hpp"
#include "scene/scene_loader.hpp"
#include "scheduling/latency_options.hpp"
#include "scheduling/thread_name.hpp"
#include "wire/host_port.hpp"

namespace felt::feltd {
namespace {

namespace asio = boost::asio;

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

}  // namespace

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
               if (nice != 0) (void)felt::step_this_thread_aside(nice);
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
    log.info("scene " + std::to_string(id.value()) + " \"" + name + "\" loaded from " + file +
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

CLI::App* add_serve_command(CLI::App& app, ServeOptions& options) {
  felt::net::ServerOptions& limits = options.limits;
  if (const char* token = std::getenv("FELT_TOKEN")) limits.token = token;
  CLI::App* serve_cmd =
      app.add_subcommand("serve", "Serve scenes over TCP and WebSocket (protocol felt.v1)");
  serve_cmd->add_option("--listen", options.listen, "HOST:PORT to listen on; port 0 picks one")
      ->capture_default_str();
  serve_cmd->add_option("--web", options.web,
                        "HOST:PORT to serve the page and its WebSocket (/ws) on; port 0 picks one "
                        "(default: off)");
  serve_cmd->add_option("--web-root", options.web_root, "The page's build folder")
      ->capture_default_str();
  serve_cmd
      ->add_option("--scene-dir", options.scene_dir, "Directory clients load scenes from by name")
      ->capture_default_str();
  serve_cmd
      ->add_option("--scene", options.scenes,
                   "Scene file to load at start; the first is the one new clients join")
      ->check(CLI::ExistingFile);
  serve_cmd
      ->add_option("--server-scenes-control", options.server_scenes_control,
                   "Who may pause, step, scale, reset, save and restore the --scene scenes: "
                   "anyone in them, or none (clients still watch, touch and change bodies)")
      ->check(CLI::IsMember({"anyone", "none"}))
      ->capture_default_str();
  serve_cmd->add_flag("--status", options.status, "Print a status line every second");
  serve_cmd
      ->add_option("--log-level", options.log_level,
                   "What to log on standard error, one line each: off, error, warning (refusals "
                   "of a limit), info (clients, scenes, shutdown) or debug (connections)")
      ->check(CLI::IsMember({"off", "error", "warning", "info", "debug"}))
      ->capture_default_str();
  serve_cmd
      ->add_option("--io-threads", options.io_threads,
                   "Threads that run the network (each client's requests stay in order)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  serve_cmd
      ->add_option("--realtime", options.realtime_priority,
                   "Run the network threads under SCHED_FIFO at this priority (1-99; 0: off) "
                   "so that haptic updates are answered at once on a busy machine")
      ->check(CLI::Range(0, felt::kMaxRealtimePriority))
      ->capture_default_str();
  serve_cmd
      ->add_option("--network-slice-us", options.network_slice_us,
                   "Time slice the network threads ask the kernel for (Linux 6.12+), so that a "
                   "haptic update preempts a busy physics thread at once (0: the kernel's)")
      ->check(CLI::Range(0, 0) | CLI::Range(static_cast<int>(felt::kMinTimeSlice.count()),
                                            static_cast<int>(felt::kMaxTimeSlice.count())))
      ->capture_default_str();
  serve_cmd
      ->add_option("--background-nice", limits.background_nice,
                   "Nice of the busy threads off the haptic path: every scene's physics and the "
                   "frame encoder (0-19; no privilege; never below feltd's own), so that a "
                   "haptic update's network thread preempts them at once (0: as the network "
                   "threads)")
      ->check(CLI::Range(0, felt::kMaxNice))
      ->capture_default_str();
  serve_cmd
      ->add_option("--cpu-wakeup-latency-us", options.cpu_wakeup_latency_us,
                   "Hold every idle core's wake-up latency at most this (system-wide, root; 0: "
                   "idle cores poll, so an update wakes the network at once; -1: the system's)")
      ->check(CLI::Range(-1, static_cast<int>(felt::kMaxCpuWakeupLatency.count())))
      ->capture_default_str();
  serve_cmd
      ->add_option("--spin-idle-cores-ms", options.spin_idle_cores_ms,
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
      ->add_option("--max-request-rate", limits.max_request_rate,
                   "Requests read a second per client, in bursts of a tenth of a second's (a "
                   "faster client waits, nothing is refused)")
      ->check(CLI::Range(100.0, 10'000'000.0))
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
  return serve_cmd;
}

}  // namespace felt::feltd
