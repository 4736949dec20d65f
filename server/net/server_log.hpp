#pragma once
// What feltd serve tells its operator on standard error, one line per event: clients that come
// and go, scenes loaded, kept and removed, refusals of a limit, shutdown. Events are rare (a
// connection, a load), never per haptic update or frame; a line is written with one write(2),
// so lines of several threads never interleave.

#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

namespace felt::net {

enum class LogLevel { kOff, kError, kWarning, kInfo, kDebug };

/// "off", "error", "warning", "info" or "debug"; nothing for anything else.
std::optional<LogLevel> parse_log_level(std::string_view name);

class ServerLog {
 public:
  /// Writes lines of `level` and more severe to file descriptor `fd`.
  explicit ServerLog(LogLevel level = LogLevel::kInfo, int fd = 2) : level_(level), fd_(fd) {}

  bool enabled(LogLevel level) const { return level != LogLevel::kOff && level <= level_; }
  /// `2026-12-06T09:52:38.123Z info  text`, when `level` is enabled.
  void write(LogLevel level, std::string_view text) const;
  void error(std::string_view text) const { write(LogLevel::kError, text); }
  void warning(std::string_view text) const { write(LogLevel::kWarning, text); }
  void info(std::string_view text) const { write(LogLevel::kInfo, text); }
  void debug(std::string_view text) const { write(LogLevel::kDebug, text); }

 private:
  LogLevel level_;
  int fd_;
};

}  // namespace felt::net
