#pragma once
// One update of a haptic proxy against a scene's haptic frame, and a local-model proxy's next
// model when one is due: what a scene renders for each ProxyUpdate (SceneRunner::render), and
// what tests/bench/remote_haptics_study renders in simulated time.

#include <cstdint>

#include "core/math/types.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/haptic_proxy.hpp"
#include "runtime/reaction_accumulator.hpp"

namespace felt {

/// The most triangles a local model carries: a 10 cm radius holds a few hundred of a fine cloth;
/// this many (about 600 KB) is a proxy asking for far more than it can reach.
inline constexpr std::size_t kMaxLocalModelTriangles = 8192;

/// Updates `proxy` with its device at `device` against `frame`'s surfaces as rendered at `now`
/// (HapticProxy::update; the reaction goes to `reactions`), and cuts its next local model when
/// its feed has one due: the frame's newer snapshot near `local`'s proxy (else the server's),
/// with the velocities of the simulation at `time_scale` (simulated over wall seconds; 0 while
/// paused: still).
ProxyOutput render_proxy(HapticProxy& proxy, const HapticFrame& frame, SteadyClock::time_point now,
                         Real time_scale, const Vec3& device, std::uint32_t buttons,
                         ReactionAccumulator& reactions, const LocalContact* local);

}  // namespace felt
