#include "scheduling/cpu_wakeup_latency.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <utility>

namespace felt {
namespace {

constexpr const char* kDevice = "/dev/cpu_dma_latency";

}  // namespace

std::expected<CpuWakeupLatencyLimit, std::string> CpuWakeupLatencyLimit::hold(
    std::chrono::microseconds limit) {
  if (limit.count() < 0 || limit > kMaxCpuWakeupLatency) {
    return std::unexpected("wake-up latency " + std::to_string(limit.count()) +
                           " us is not in 0 to " + std::to_string(kMaxCpuWakeupLatency.count()));
  }
  const int fd = ::open(kDevice, O_WRONLY | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    return std::unexpected(std::string(kDevice) + ": " + std::strerror(error) +
                           (error == EACCES ? " (it takes root)" : ""));
  }
  // the request is one binary 32-bit value in microseconds
  const auto value = static_cast<std::int32_t>(limit.count());
  if (::write(fd, &value, sizeof value) != static_cast<ssize_t>(sizeof value)) {
    const int error = errno;
    ::close(fd);
    return std::unexpected(std::string(kDevice) + ": " + std::strerror(error));
  }
  return CpuWakeupLatencyLimit(fd);
}

CpuWakeupLatencyLimit::CpuWakeupLatencyLimit(CpuWakeupLatencyLimit&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)) {}

CpuWakeupLatencyLimit& CpuWakeupLatencyLimit::operator=(CpuWakeupLatencyLimit&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

CpuWakeupLatencyLimit::~CpuWakeupLatencyLimit() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<std::chrono::microseconds> cpu_wakeup_latency_limit() {
  const int fd = ::open(kDevice, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  std::int32_t value = 0;
  const bool read_one = ::read(fd, &value, sizeof value) == static_cast<ssize_t>(sizeof value);
  ::close(fd);
  if (!read_one) return std::nullopt;
  return std::chrono::microseconds{value};
}

}  // namespace felt
