#pragma once
// The haptic devices that live in the server: each follows its script and drives a proxy, one
// update per servo tick. The servo thread ticks them against the wall clock; `feltd run` ticks
// them in simulated time between steps, which makes a run with devices reproducible.

#include <iosfwd>
#include <vector>

#include "device/haptic_recording.hpp"
#include "runtime/haptic_proxy.hpp"
#include "scene/scene.hpp"

namespace felt {

/// Devices that follow recorded paths: one per device index of `records`, through its
/// records' positions and buttons at their times.
std::vector<ScriptedDevice> devices_from_recording(const std::vector<HapticRecord>& records);

class ScriptedDevices {
 public:
  /// Proxies for `devices` with `settings`: the server's own (client 0), numbered as the devices.
  ScriptedDevices(const std::vector<ScriptedDevice>& devices, const ProxySettings& settings);

  bool empty() const { return devices_.empty(); }
  std::size_t size() const { return devices_.size(); }

  /// Updates every device at script time `t` (seconds since the script started), `dt` after
  /// the previous tick, against `surface`.
  void tick(const HapticSurface& surface, Real t, Real dt, ReactionAccumulator& reactions);

  /// Each device's latest update, in scene order.
  const std::vector<HapticRecord>& latest() const { return latest_; }
  /// Writes every later tick's records to `out` (null: stop recording).
  void record_to(std::ostream* out);
  /// Closes the proxies' reactions.
  void close(ReactionAccumulator& reactions) const;

 private:
  std::vector<ScriptedDevice> devices_;
  std::vector<HapticProxy> proxies_;
  std::vector<HapticRecord> latest_;
  std::ostream* recording_ = nullptr;
};

}  // namespace felt
