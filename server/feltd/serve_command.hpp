#pragma once
// `feltd serve`: the scenes served over TCP (and the page and its WebSocket) until SIGINT or
// SIGTERM, and the flags that shape it.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "net/server.hpp"

namespace felt::feltd {

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

/// Adds `serve` and its flags to `app`, to be read into `options`; returns the subcommand.
CLI::App* add_serve_command(CLI::App& app, ServeOptions& options);

/// Serves until a signal ends it; returns the exit status.
int serve(const ServeOptions& options);

}  // namespace felt::feltd
