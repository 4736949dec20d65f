#include "runtime/scene_members.hpp"

#include <algorithm>

namespace felt {

void SceneMembers::join(Member member) {
  std::lock_guard lock(mutex_);
  const auto same = std::find_if(members_.begin(), members_.end(),
                                 [&](const Member& m) { return m.client == member.client; });
  if (same != members_.end()) {
    *same = std::move(member);  // a client is in a scene once
  } else {
    members_.push_back(std::move(member));
  }
}

void SceneMembers::leave(ClientId client) {
  std::lock_guard lock(mutex_);
  std::erase_if(members_, [client](const Member& m) { return m.client == client; });
}

std::size_t SceneMembers::count() const {
  std::lock_guard lock(mutex_);
  return members_.size();
}

bool SceneMembers::contains(ClientId client) const {
  std::lock_guard lock(mutex_);
  return std::any_of(members_.begin(), members_.end(),
                     [client](const Member& m) { return m.client == client; });
}

std::string SceneMembers::name_of(ClientId client) const {
  std::lock_guard lock(mutex_);
  for (const Member& m : members_) {
    if (m.client == client) return m.name;
  }
  return {};
}

void SceneMembers::broadcast(SceneEvent event) {
  send(event, true);
}

void SceneMembers::broadcast_to_all(SceneEvent event) {
  send(event, false);
}

void SceneMembers::send(SceneEvent& event, bool skip_origin) {
  // listeners are called under the lock so that sequence numbers reach each of them in order;
  // they only post the event to their own thread
  std::lock_guard lock(mutex_);
  event.sequence = ++sequence_;
  if (event.client_name.empty() && event.client != 0) {
    for (const Member& m : members_) {
      if (m.client == event.client) event.client_name = m.name;
    }
  }
  for (const Member& m : members_) {
    if (skip_origin && m.client == event.client) continue;
    if (auto listener = m.listener.lock()) listener->on_scene_event(event);
  }
}

}  // namespace felt
