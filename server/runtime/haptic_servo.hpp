#pragma once
// The haptic servo thread of a scene (docs/architecture.md, "Threads and data flow"): ticks the
// scene's scripted devices at the servo rate (250–4000 Hz) against the wall clock, each tick
// rendering against the surfaces interpolated between the two latest physics snapshots.

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "runtime/haptic_frame.hpp"
#include "runtime/scripted_devices.hpp"

namespace felt {

struct ServoStats {
  std::uint64_t ticks = 0;
  std::uint64_t late_ticks = 0;  ///< ticks that started more than one period late
  double mean_tick_us = 0;       ///< time to update every device, over all ticks
  double max_tick_us = 0;
};

class HapticServo {
 public:
  using FrameSource = std::function<std::shared_ptr<const HapticFrame>()>;

  HapticServo(ScriptedDevices devices, Real rate_hz, FrameSource frames,
              ReactionAccumulator& reactions);
  ~HapticServo();
  HapticServo(const HapticServo&) = delete;
  HapticServo& operator=(const HapticServo&) = delete;

  void start();
  void stop();

  ServoStats stats() const;
  /// Each device's latest update.
  std::vector<HapticRecord> latest() const;

 private:
  void run(std::stop_token stop);

  ScriptedDevices devices_;  ///< touched by the servo thread only, once started
  Real rate_hz_;
  FrameSource frames_;
  ReactionAccumulator& reactions_;

  mutable std::mutex mutex_;  ///< guards the two below
  ServoStats stats_;
  std::vector<HapticRecord> latest_;
  std::jthread thread_;
};

}  // namespace felt
