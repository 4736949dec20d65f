#pragma once
// What the haptic loop renders against: the two latest physics snapshots and, per body, a
// broad-phase structure bounding each triangle over the motion between them. Published by the
// physics thread after its steps (only while some proxy is in use: a scene nobody touches pays
// nothing) and read by any thread, like the snapshots.

#include <chrono>
#include <memory>
#include <vector>

#include "core/collision/triangle_query.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "runtime/snapshot.hpp"

namespace felt {

using SteadyClock = std::chrono::steady_clock;

struct HapticFrame {
  std::shared_ptr<const SceneSnapshot> from;  ///< the older snapshot (= to for the first frame)
  std::shared_ptr<const SceneSnapshot> to;
  /// per body of `to`, where it was in `from`: the same body with the same surface, or itself
  /// (still) when it is new (bodies come and go; a reset scene has new surfaces under old ids)
  std::vector<const BodySnapshot*> older;
  /// per body of `to`, bounds over [older, to]; written only while the frame is being made
  std::vector<std::unique_ptr<TriangleQuery>> queries;
  std::vector<SurfaceMotion> motion;  ///< per body, from older to `to` and along its chain
  /// holds `from` and `to` for surfaces kept after the frame is recycled
  std::shared_ptr<const void> storage;
  SteadyClock::time_point published;  ///< when `to` became the latest snapshot
  /// wall time from the publication of `from` to that of `to`: the render goes from `from` to
  /// `to` over the same time after `to` is published (Zhuang & Canny: one step behind)
  SteadyClock::duration interval{0};

  /// The surfaces rendered at wall time `now`.
  HapticSurface surface(SteadyClock::time_point now) const;
  /// The surfaces at `alpha` of the way from `from` to `to`.
  HapticSurface surface_at(Real alpha) const;
};

/// The frame for the new snapshot `to`, following `previous` (null for the first: a still
/// surface). `recycled`, when given, is a retired frame nobody reads any more: its structures
/// are refitted instead of copied.
std::shared_ptr<HapticFrame> make_haptic_frame(std::shared_ptr<const SceneSnapshot> to,
                                               const HapticFrame* previous,
                                               std::shared_ptr<HapticFrame> recycled,
                                               TriangleQueryKind kind, SteadyClock::time_point now);

}  // namespace felt
