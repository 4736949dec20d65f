#include "runtime/scene_registry.hpp"

#include <algorithm>

namespace felt {
namespace {

std::uint32_t index_of(SceneId id) {
  return static_cast<std::uint32_t>(id & 0xffffffffu);
}
std::uint32_t generation_of(SceneId id) {
  return static_cast<std::uint32_t>(id >> 32);
}

}  // namespace

SceneId SceneRegistry::add(std::shared_ptr<SceneRunner> runner) {
  std::lock_guard lock(mutex_);
  auto free = std::find_if(slots_.begin(), slots_.end(), [](const Slot& s) { return !s.runner; });
  if (free == slots_.end()) free = slots_.insert(slots_.end(), Slot{});
  // generations start at 1 so that no id is 0
  ++free->generation;
  free->runner = std::move(runner);
  const auto index = static_cast<std::uint32_t>(free - slots_.begin());
  return (SceneId{free->generation} << 32) | index;
}

std::shared_ptr<SceneRunner> SceneRegistry::find(SceneId id) const {
  std::lock_guard lock(mutex_);
  const std::uint32_t index = index_of(id);
  if (index >= slots_.size() || slots_[index].generation != generation_of(id)) return nullptr;
  return slots_[index].runner;
}

bool SceneRegistry::remove(SceneId id) {
  std::shared_ptr<SceneRunner> removed;
  {
    std::lock_guard lock(mutex_);
    const std::uint32_t index = index_of(id);
    if (index >= slots_.size() || slots_[index].generation != generation_of(id)) return false;
    removed = std::move(slots_[index].runner);
  }
  if (!removed) return false;
  removed->stop();
  return true;
}

void SceneRegistry::remove_if_unused(SceneId id) {
  std::shared_ptr<SceneRunner> removed;
  {
    std::lock_guard lock(mutex_);
    const std::uint32_t index = index_of(id);
    if (index >= slots_.size() || slots_[index].generation != generation_of(id)) return;
    if (slots_[index].runner.use_count() != 1) return;
    removed = std::move(slots_[index].runner);
  }
  removed->stop();
}

void SceneRegistry::stop_all() {
  std::vector<std::shared_ptr<SceneRunner>> runners;
  {
    std::lock_guard lock(mutex_);
    for (const Slot& slot : slots_) {
      if (slot.runner) runners.push_back(slot.runner);
    }
  }
  for (const auto& runner : runners) runner->stop();
}

std::size_t SceneRegistry::size() const {
  std::lock_guard lock(mutex_);
  return static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(),
                                                [](const Slot& s) { return s.runner != nullptr; }));
}

}  // namespace felt
