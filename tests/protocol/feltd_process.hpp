#pragma once
// The real feltd binary as a child process, for end-to-end tests.

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace felt::test {

class FeltdProcess {
 public:
  /// Starts `feltd serve --listen 127.0.0.1:0 ARGS...` (without --listen, feltd's default, when
  /// `default_listen`) and reads the port from its first line, which must say 127.0.0.1, and
  /// with `--web` in ARGS the web port from the second.
  /// Throws std::runtime_error when it does not come up.
  explicit FeltdProcess(const std::vector<std::string>& args, bool default_listen = false);
  ~FeltdProcess();
  FeltdProcess(const FeltdProcess&) = delete;
  FeltdProcess& operator=(const FeltdProcess&) = delete;

  std::uint16_t port() const { return port_; }
  /// The web port (0 without --web).
  std::uint16_t web_port() const { return web_port_; }
  pid_t pid() const { return pid_; }
  const std::string& first_line() const { return first_line_; }

  /// Sends `signal` and waits for the exit; the exit status, or nothing on timeout (scaled, as
  /// the wait for its first line is: support/time_scale.hpp).
  std::optional<int> stop(int signal, std::chrono::milliseconds timeout);
  /// Whether the process is still running.
  bool running();

 private:
  /// The next line feltd prints, without its newline; throws past `deadline`.
  std::string read_line(std::chrono::steady_clock::time_point deadline);

  pid_t pid_ = -1;
  int stdout_fd_ = -1;
  std::uint16_t port_ = 0;
  std::uint16_t web_port_ = 0;
  std::string first_line_;
};

}  // namespace felt::test
