#pragma once
// The haptic frames a scene's proxies render against, made from its latest snapshot: by the
// physics thread after each publication while some proxy was rendered lately (a scene nobody
// touches pays nothing), or by the first render after an idle spell. The frames made lately
// are pooled, and one nobody reads any more is refitted instead of copied.

#include <memory>
#include <mutex>
#include <vector>

#include "core/collision/triangle_query.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/live_scene.hpp"
#include "runtime/published.hpp"

namespace felt {

class LiveHapticFrames {
 public:
  /// Frames are made with structures of kind `structure` from `live`'s latest snapshots.
  LiveHapticFrames(LiveScene& live, TriangleQueryKind structure)
      : live_(live), structure_(structure) {}

  /// The frame to render against now (made now from the latest snapshot if no proxy was used
  /// lately); the proxies count as in use from now. Any thread.
  std::shared_ptr<const HapticFrame> current();
  /// The frame for the snapshot just published, if proxies are in use. The physics thread.
  void publish(SteadyClock::time_point now);

 private:
  /// The latest snapshot's frame after `previous` (null: a still one), refitting a pooled
  /// frame nobody reads any more when there is one; with mutex_ held.
  std::shared_ptr<HapticFrame> make_pooled(const HapticFrame* previous,
                                           SteadyClock::time_point now);

  LiveScene& live_;  ///< told of every render (LiveScene::render_haptics)
  TriangleQueryKind structure_;
  Published<HapticFrame> latest_;
  /// the frames made lately; one nobody else holds any more is refitted, not copied
  std::vector<std::shared_ptr<HapticFrame>> pool_;
  std::mutex mutex_;  ///< held while a frame is made
};

}  // namespace felt
