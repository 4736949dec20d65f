#pragma once
// A scene as its physics thread keeps it between steps: the World, its pacing, the steps and
// forces requests asked for, who owns each body; and what it publishes for the other threads
// (snapshots and the body catalog). Everything but the publications belongs to the physics
// thread once it has started (before that, to whoever starts it); the publications are read by
// any thread.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "runtime/body_catalog.hpp"
#include "runtime/clock.hpp"
#include "runtime/pacer.hpp"
#include "runtime/published.hpp"
#include "runtime/recent_use.hpp"
#include "runtime/scene_event.hpp"
#include "runtime/scene_status.hpp"
#include "runtime/snapshot.hpp"
#include "runtime/step_requests.hpp"
#include "runtime/timed_forces.hpp"
#include "scene/scene.hpp"

namespace felt {

class LiveScene {
 public:
  /// `scene`, its bodies owned by `owner`, paced by `clock`; publishes its first snapshot and
  /// catalog.
  LiveScene(Scene scene, ClientId owner, const Clock& clock);

  Scene scene;
  Pacer pacer;
  StepRequests step_requests;
  TimedForces timed_forces;

  SceneStatus status() const;
  /// An event of `kind` caused by `by`, stamped with the scene's step, time and time scale.
  SceneEvent event(SceneEvent::Kind kind, ClientId by) const;

  /// The latest snapshot (never null) and catalog (never null); any thread. Reading the
  /// snapshot keeps snapshots coming after steps for kReadersKept (publish_steps).
  std::shared_ptr<const SceneSnapshot> latest() const {
    read_.use(kReadersKept);
    return latest_.load();
  }
  std::shared_ptr<const BodyCatalog> bodies() const { return catalog_.load(); }
  /// Snapshots published so far: the latest one's version.
  std::uint64_t published() const { return published_; }

  /// Publishes a snapshot of the world now: with vertex normals while haptics render against
  /// the snapshots (render_haptics in the last kHapticsKept), without otherwise.
  void publish();
  /// After steps: publishes a snapshot of them while someone read one lately (latest() in the
  /// last kReadersKept); else leaves the latest as it was, stale, until catch_up. A scene
  /// nobody watches makes no snapshot nobody would see (a tenth of a step of the three cubes,
  /// whose embedded surfaces it places; docs/results/feature_costs.md).
  void publish_steps();
  /// Publishes the steps publish_steps left out, if someone read lately.
  void catch_up();
  /// The latest snapshot lacks steps since taken (publish_steps). Any thread.
  bool stale() const { return stale_.load(std::memory_order_relaxed); }
  static constexpr auto kReadersKept = std::chrono::seconds(1);
  /// A proxy renders haptics against the snapshots at `now`: for kHapticsKept the snapshots
  /// carry vertex normals (force shading and local models read them) and LiveHapticFrames
  /// makes frames after each publication. Whether haptics rendered within kHapticsKept before.
  /// Any thread.
  bool render_haptics(std::chrono::steady_clock::time_point now) {
    return haptics_.use(kHapticsKept, now);
  }
  /// Whether a proxy rendered within kHapticsKept of `now`. Any thread.
  bool haptics_rendering(std::chrono::steady_clock::time_point now) const {
    return haptics_.recent(kHapticsKept, now);
  }
  static constexpr auto kHapticsKept = std::chrono::seconds(1);
  /// A local-model proxy renders in the scene: its snapshots carry each body's point compliance
  /// from now on (the bodies' stiffness for the local models; two sparse factorizations per body
  /// every kComplianceRefresh on a thread of their own, which a scene no remote device touches
  /// does not pay). Any thread.
  void serve_local_models() { local_models_.store(true, std::memory_order_relaxed); }
  /// Publishes a snapshot and a catalog after bodies came or went.
  void publish_bodies();
  /// Every body of the scene now belongs to its owner (a new or a reset scene).
  void own_scene_bodies();
  /// Body `id`, just added by `client`, belongs to it.
  void add_owner(BodyId id, ClientId client) { owners_.emplace_back(id, client); }
  /// Body `id` is gone.
  void forget_owner(BodyId id);

 private:
  void publish_catalog();

  ClientId owner_;
  Published<SceneSnapshot> latest_;
  std::uint64_t published_ = 0;
  std::atomic<bool> local_models_{false};
  RecentUse haptics_;       ///< render_haptics
  mutable RecentUse read_;  ///< of the latest snapshot
  std::atomic<bool> stale_{false};
  /// started by the first snapshot that needs it, on the physics thread (whose nice it takes)
  ComplianceWorker compliance_{ComplianceWorker::Mode::kThread};
  Published<BodyCatalog> catalog_;
  /// the owner of each body, by id; published through catalog_
  std::vector<std::pair<BodyId, ClientId>> owners_;
};

}  // namespace felt
