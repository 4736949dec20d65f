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

SceneRegistry::Slot* SceneRegistry::slot(SceneId id) {
  const std::uint32_t index = index_of(id);
  if (index >= slots_.size() || slots_[index].generation != generation_of(id)) return nullptr;
  return slots_[index].runner ? &slots_[index] : nullptr;
}

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

std::shared_ptr<SceneRunner> SceneRegistry::join(SceneId id, SceneMembers::Member member) {
  std::lock_guard lock(mutex_);
  Slot* found = slot(id);
  if (!found) return nullptr;
  found->runner->members().join(std::move(member));
  return found->runner;
}

void SceneRegistry::leave(SceneId id, ClientId client) {
  std::shared_ptr<SceneRunner> removed;
  {
    std::lock_guard lock(mutex_);
    Slot* found = slot(id);
    if (!found) return;
    found->runner->members().leave(client);
    if (found->runner->members().count() > 0 || found->runner->access().persistent) return;
    removed = std::move(found->runner);
  }
  removed->stop();
}

bool SceneRegistry::remove(SceneId id) {
  std::shared_ptr<SceneRunner> removed;
  {
    std::lock_guard lock(mutex_);
    Slot* found = slot(id);
    if (!found) return false;
    removed = std::move(found->runner);
  }
  removed->stop();
  return true;
}

void SceneRegistry::stop_all() {
  for (const auto& [id, runner] : list()) runner->stop();
}

std::size_t SceneRegistry::size() const {
  std::lock_guard lock(mutex_);
  return static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(),
                                                [](const Slot& s) { return s.runner != nullptr; }));
}

std::vector<std::pair<SceneId, std::shared_ptr<SceneRunner>>> SceneRegistry::list() const {
  std::lock_guard lock(mutex_);
  std::vector<std::pair<SceneId, std::shared_ptr<SceneRunner>>> scenes;
  for (std::uint32_t i = 0; i < slots_.size(); ++i) {
    if (slots_[i].runner) {
      scenes.emplace_back((SceneId{slots_[i].generation} << 32) | i, slots_[i].runner);
    }
  }
  return scenes;
}

}  // namespace felt
