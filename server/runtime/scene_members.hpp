#pragma once
// The clients in a scene, and the fan-out of the scene's events to them.

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "runtime/scene_event.hpp"

namespace felt {

/// A client in a scene (a session). Called from any thread; must not block.
class SceneListener {
 public:
  virtual ~SceneListener() = default;
  virtual void on_scene_event(const SceneEvent& event) = 0;
};

class SceneMembers {
 public:
  struct Member {
    ClientId client = 0;
    std::string name;
    std::weak_ptr<SceneListener> listener;
  };

  void join(Member member);
  void leave(ClientId client);
  std::size_t count() const;
  bool contains(ClientId client) const;
  /// The name `client` joined with (empty when it is not a member).
  std::string name_of(ClientId client) const;
  /// Gives `event` the scene's next sequence number and sends it to every member except
  /// `event.client` (which has its reply).
  void broadcast(SceneEvent event);
  /// Sends `event` to every member, `event.client` included (the scene's end).
  void broadcast_to_all(SceneEvent event);

 private:
  void send(SceneEvent& event, bool skip_origin);

  mutable std::mutex mutex_;
  std::vector<Member> members_;
  std::uint64_t sequence_ = 0;
};

}  // namespace felt
