#pragma once
// Changes to a scene from other threads, applied by the physics thread between steps, never
// during one.

#include <functional>
#include <mutex>
#include <vector>

#include "scene/scene.hpp"

namespace felt {

using SceneCommand = std::function<void(Scene&)>;

class CommandQueue {
 public:
  void push(SceneCommand command) {
    std::lock_guard lock(mutex_);
    pending_.push_back(std::move(command));
  }

  /// Runs every queued command on `scene`, in the order they were pushed.
  void apply_all(Scene& scene) {
    {
      std::lock_guard lock(mutex_);
      running_.swap(pending_);
    }
    for (SceneCommand& command : running_) command(scene);
    running_.clear();
  }

 private:
  std::mutex mutex_;
  std::vector<SceneCommand> pending_;
  std::vector<SceneCommand> running_;  ///< only touched by the physics thread
};

}  // namespace felt
