#include "runtime/haptic_servo.hpp"

#include <algorithm>
#include <chrono>

#include "scheduling/thread_name.hpp"

namespace felt {

HapticServo::HapticServo(ScriptedDevices devices, Real rate_hz, FrameSource frames,
                         ReactionAccumulator& reactions)
    : devices_(std::move(devices)),
      rate_hz_(rate_hz),
      frames_(std::move(frames)),
      reactions_(reactions),
      latest_(devices_.latest()) {}

HapticServo::~HapticServo() {
  stop();
}

void HapticServo::start() {
  if (thread_.joinable()) return;
  thread_ = std::jthread([this](std::stop_token stop) { run(stop); });
  name_thread(thread_.native_handle(), "felt-servo");
}

void HapticServo::stop() {
  if (!thread_.joinable()) return;
  thread_.request_stop();
  thread_.join();
  devices_.close(reactions_);
}

ServoStats HapticServo::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::vector<HapticRecord> HapticServo::latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

void HapticServo::run(std::stop_token stop) {
  using Seconds = std::chrono::duration<double>;
  const auto period = std::chrono::duration_cast<SteadyClock::duration>(Seconds(1 / rate_hz_));
  const SteadyClock::time_point origin = SteadyClock::now();
  SteadyClock::time_point due = origin;
  SteadyClock::time_point previous = origin;
  double total_us = 0;
  while (!stop.stop_requested()) {
    const SteadyClock::time_point start = SteadyClock::now();
    const auto frame = frames_();
    devices_.tick(frame->surface(start), Seconds(start - origin).count(),
                  Seconds(start - previous).count(), reactions_);
    previous = start;
    const double tick_us = 1e6 * Seconds(SteadyClock::now() - start).count();
    total_us += tick_us;
    {
      std::lock_guard lock(mutex_);
      ++stats_.ticks;
      if (start - due > period) ++stats_.late_ticks;
      stats_.mean_tick_us = total_us / static_cast<double>(stats_.ticks);
      stats_.max_tick_us = std::max(stats_.max_tick_us, tick_us);
      latest_ = devices_.latest();
    }
    // a servo that fell behind skips the ticks it missed rather than bursting to catch up
    due = std::max(due + period, SteadyClock::now() - period);
    std::this_thread::sleep_until(due);
  }
}

}  // namespace felt
