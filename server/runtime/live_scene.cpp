#include "runtime/live_scene.hpp"

#include <algorithm>

namespace felt {

LiveScene::LiveScene(Scene scene_in, ClientId owner, const Clock& clock)
    : scene(std::move(scene_in)), pacer(clock, scene.world.settings().time_step), owner_(owner) {
  own_scene_bodies();
  publish();
  publish_catalog();
}

SceneStatus LiveScene::status() const {
  return {scene.world.step_count(), scene.world.time(), pacer.paused(), pacer.scale()};
}

SceneEvent LiveScene::event(SceneEvent::Kind kind, ClientId by) const {
  SceneEvent e;
  e.kind = kind;
  e.client = by;
  e.step = scene.world.step_count();
  e.sim_time = scene.world.time();
  e.time_scale = pacer.scale();
  return e;
}

void LiveScene::publish() {
  auto snapshot =
      make_snapshot(scene.world, latest_.load().get(),
                    local_models_.load(std::memory_order_relaxed) ? &compliance_ : nullptr,
                    haptics_rendering(std::chrono::steady_clock::now()) ? VertexNormals::kComputed
                                                                        : VertexNormals::kLeftOut);
  snapshot->version = ++published_;
  latest_.store(std::move(snapshot));
  stale_.store(false, std::memory_order_relaxed);
}

void LiveScene::publish_steps() {
  if (read_.recent(kReadersKept)) {
    publish();
  } else {
    stale_.store(true, std::memory_order_relaxed);
  }
}

void LiveScene::catch_up() {
  if (stale() && read_.recent(kReadersKept)) publish();
}

void LiveScene::publish_bodies() {
  // the snapshot first: a client told of a body finds it in the next frame
  publish();
  publish_catalog();
}

void LiveScene::own_scene_bodies() {
  owners_.clear();
  for (BodyId id : scene.world.body_ids()) owners_.emplace_back(id, owner_);
}

void LiveScene::forget_owner(BodyId id) {
  std::erase_if(owners_, [id](const auto& owner) { return owner.first == id; });
}

void LiveScene::publish_catalog() {
  auto catalog = std::make_shared<BodyCatalog>();
  for (BodyId id : scene.world.body_ids()) {
    const auto owner = std::find_if(owners_.begin(), owners_.end(),
                                    [id](const auto& entry) { return entry.first == id; });
    catalog->bodies.push_back(
        describe_body(scene.world, id, owner == owners_.end() ? 0 : owner->second));
  }
  catalog_.store(std::move(catalog));
}

}  // namespace felt
