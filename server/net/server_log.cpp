#include "net/server_log.hpp"

#include <unistd.h>

#include <array>
#include <chrono>
#include <ctime>

namespace felt::net {

namespace {

constexpr std::array<std::string_view, 5> kLevelNames = {"off", "error", "warning", "info",
                                                         "debug"};

/// The wall clock in UTC, to the millisecond: 2026-12-06T09:52:38.123Z.
std::string utc_now() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(text + n, sizeof text - n, ".%03dZ", static_cast<int>(millis));
  return text;
}

}  // namespace

std::optional<LogLevel> parse_log_level(std::string_view name) {
  for (std::size_t level = 0; level < kLevelNames.size(); ++level) {
    if (kLevelNames[level] == name) return static_cast<LogLevel>(level);
  }
  return std::nullopt;
}

void ServerLog::write(LogLevel level, std::string_view text) const {
  if (!enabled(level)) return;
  std::string line = utc_now();
  line += ' ';
  const std::string_view name = kLevelNames[static_cast<std::size_t>(level)];
  line += name;
  line.append(8 - name.size(), ' ');  // the texts line up
  // a client's name is free text: a control character in it must not start a line of its own
  for (const char c : text) line += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  line += '\n';
  // one write(2) per line, which a pipe takes whole up to PIPE_BUF bytes, so that the lines of
  // several threads never interleave (a log that cannot be written is lost)
  for (std::size_t done = 0; done < line.size();) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace felt::net
