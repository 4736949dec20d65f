#pragma once
// Remote haptics in simulated time (issue 26; docs/results/remote_haptics.md, the deterministic
// section): a scene's World stepped at its time step with the haptic pipeline feltd renders with
// (render_proxy, the reaction accumulator, haptic frames of its snapshots), a client that sends
// a scripted device path and renders what comes back (round trips, or the real LocalRenderer at
// 1 kHz), and between them a channel that delays felt.v1 messages by a fixed one-way time, with
// optional seeded jitter and loss. No sockets and no wall clock: the same case gives the same
// samples, bit for bit, on every run.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/math/types.hpp"
#include "device/device_path.hpp"

namespace felt::study {

/// The simulated network, each direction: half the round trip, normally distributed jitter with
/// half `jitter`'s standard deviation (as tc netem splits a round trip's jitter), and messages
/// lost with probability `loss` that arrive a TCP retransmission timeout later, holding back
/// those behind them (the protocol runs over TCP, which delivers in order).
struct SimulatedNetwork {
  double round_trip = 0;  ///< s
  double jitter = 0;      ///< s, of the round trip
  double loss = 0;        ///< probability per message
  std::uint64_t seed = 1;
};

/// s: what a lost message waits for (Linux's minimum retransmission timeout).
inline constexpr double kRetransmissionTimeout = 0.2;

enum class Rendering {
  kRoundTrip,   ///< a ProxyUpdate every tick; the device feels the latest ForceUpdate
  kLocalModel,  ///< LocalRenderer at the device rate, ProxyUpdates at `upstream_rate`
};

struct RemoteCase {
  std::filesystem::path scene;  ///< a scene file, loaded as feltd loads it
  DevicePath path;
  double duration = 3;        ///< s of the path
  double device_rate = 1000;  ///< Hz
  Rendering rendering = Rendering::kRoundTrip;
  SimulatedNetwork network;
  double upstream_rate = 250;  ///< Hz, local model
  double model_radius = 0.1;   ///< m, local model
  double device_damping = 20;  ///< N·s/m the local renderer counts on (LocalRendererOptions)
};

/// One device tick: for round trips the update sent then and the reply to it (`answered`
/// false when none came before the path ended); for the local model what the device rendered.
struct RemoteSample {
  double time = 0;  ///< s
  Vec3 device = Vec3::Zero();
  bool answered = false;
  Vec3 force = Vec3::Zero();
  bool in_contact = false;
  Vec3 proxy = Vec3::Zero();
  double round_trip = 0;  ///< s: of this update (round trips) or the last measured (local)
};

/// The study's device paths (3 s): 0.5 s to 1 cm above the surface (the 2 cm proxy touches 2 cm
/// above it), 0.5 s pressing below the surface's rest, 1 s sliding across, 0.5 s pulling out,
/// 0.5 s away. The cube (scenes/pressed_cube.json, z up) from above, 1.5 cm into its top, 10 cm
/// across; the curtain (scenes/default.json) as scripts/bench-remote-haptics's, 3 cm behind its
/// rest, 20 cm across ("toward -z" is into both surfaces).
DevicePath cube_press_path();
DevicePath curtain_press_path();

/// Runs `c`; throws std::runtime_error when its scene does not load.
std::vector<RemoteSample> run_remote_case(const RemoteCase& c);

/// Writes `samples` as `felt touch --log` does (the columns scripts/lib/remote_haptics.py
/// reads); unanswered updates are left out, as there.
void write_remote_log(const std::filesystem::path& file, const std::vector<RemoteSample>& samples);

}  // namespace felt::study
