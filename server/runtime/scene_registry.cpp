#include "runtime/scene_registry.hpp"

#include <algorithm>

namespace felt {
namespace {

std::uint32_t index_of(SceneId id) {
  return static_cast<std::uint32_t>(id.value() & 0xffffffffu);
}
std::uint32_t generation_of(SceneId id) {
  return static_cast<std::uint32_t>(id.value() >> 32);
}
SceneId id_of(std::uint32_t generation, std::uint32_t index) {
  return (std::uint64_t{generation} << 32) | index;
}

}  // namespace

SceneRegistry::SceneRegistry() : retirer_([this](std::stop_token stop) { retire_loop(stop); }) {}

SceneRegistry::~SceneRegistry() {
  stop_all();
}

void SceneRegistry::retire(std::shared_ptr<SceneRunner> runner) {
  {
    std::lock_guard lock(retiring_mutex_);
    retiring_.push_back(std::move(runner));
  }
  retiring_wake_.notify_all();
}

void SceneRegistry::retire_loop(std::stop_token stop) {
  std::unique_lock lock(retiring_mutex_);
  while (retiring_wake_.wait(lock, stop, [this] { return !retiring_.empty(); })) {
    std::vector<std::shared_ptr<SceneRunner>> batch;
    batch.swap(retiring_);
    stopping_ = batch.size();
    lock.unlock();
    for (const auto& runner : batch) runner->stop();
    batch.clear();  // their last references go here, not on a network thread
    lock.lock();
    stopping_ = 0;
    retiring_wake_.notify_all();
  }
}

SceneRegistry::Slot* SceneRegistry::slot(SceneId id) {
  const std::uint32_t index = index_of(id);
  if (index >= slots_.size() || slots_[index].generation != generation_of(id)) return nullptr;
  return slots_[index].runner ? &slots_[index] : nullptr;
}

SceneId SceneRegistry::add(std::shared_ptr<SceneRunner> runner,
                           std::optional<SceneMembers::Member> first) {
  std::lock_guard lock(mutex_);
  if (first) runner->members().join(std::move(*first));
  auto free = std::find_if(slots_.begin(), slots_.end(), [](const Slot& s) { return !s.runner; });
  if (free == slots_.end()) free = slots_.insert(slots_.end(), Slot{});
  // generations start at 1 so that no id is 0
  ++free->generation;
  free->runner = std::move(runner);
  const auto index = static_cast<std::uint32_t>(free - slots_.begin());
  return id_of(free->generation, index);
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

bool SceneRegistry::leave(SceneId id, ClientId client) {
  std::shared_ptr<SceneRunner> removed;
  {
    std::lock_guard lock(mutex_);
    Slot* found = slot(id);
    if (!found) return false;
    found->runner->members().leave(client);
    if (found->runner->members().count() > 0 || found->runner->access().persistent) return false;
    removed = std::move(found->runner);
  }
  retire(std::move(removed));
  return true;
}

bool SceneRegistry::remove(SceneId id) {
  std::shared_ptr<SceneRunner> removed;
  {
    std::lock_guard lock(mutex_);
    Slot* found = slot(id);
    if (!found) return false;
    removed = std::move(found->runner);
  }
  retire(std::move(removed));
  return true;
}

void SceneRegistry::stop_all() {
  for (const auto& [id, runner] : list()) runner->stop();
  // and wait until the retiring thread has stopped the scenes removed before
  std::unique_lock lock(retiring_mutex_);
  retiring_wake_.wait(lock, [this] { return retiring_.empty() && stopping_ == 0; });
}

std::size_t SceneRegistry::size() const {
  std::lock_guard lock(mutex_);
  return static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(),
                                                [](const Slot& s) { return s.runner != nullptr; }));
}

std::size_t SceneRegistry::kept_by(ClientId owner) const {
  std::lock_guard lock(mutex_);
  return static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(), [&](const Slot& s) {
    return s.runner && s.runner->access().persistent && s.runner->access().owner == owner;
  }));
}

std::vector<std::pair<SceneId, std::shared_ptr<SceneRunner>>> SceneRegistry::list() const {
  std::lock_guard lock(mutex_);
  std::vector<std::pair<SceneId, std::shared_ptr<SceneRunner>>> scenes;
  for (std::uint32_t i = 0; i < slots_.size(); ++i) {
    if (slots_[i].runner) {
      scenes.emplace_back(id_of(slots_[i].generation, i), slots_[i].runner);
    }
  }
  return scenes;
}

}  // namespace felt
