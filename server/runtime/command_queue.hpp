#pragma once
// Changes to a scene from other threads, applied by the physics thread between steps, never
// during one. A command that will never run (its scene stopped) is cancelled instead, so that
// whoever waits for it hears so.

#include <functional>
#include <mutex>
#include <vector>

#include "scene/scene.hpp"

namespace felt {

using SceneCommand = std::function<void(Scene&)>;

class CommandQueue {
 public:
  /// Queues `run`; `cancel` is called instead if the queue is closed before it runs. Returns
  /// false (and calls `cancel`) when the queue is already closed.
  bool push(SceneCommand run, std::function<void()> cancel = {}) {
    {
      std::lock_guard lock(mutex_);
      if (!closed_) {
        pending_.push_back({std::move(run), std::move(cancel)});
        return true;
      }
    }
    if (cancel) cancel();
    return false;
  }

  /// Runs every queued command on `scene`, in the order they were pushed.
  void apply_all(Scene& scene) {
    {
      std::lock_guard lock(mutex_);
      running_.swap(pending_);
    }
    for (Command& command : running_) command.run(scene);
    running_.clear();
  }

  bool empty() const {
    std::lock_guard lock(mutex_);
    return pending_.empty();
  }

  /// Cancels what is queued and every later push.
  void close() {
    std::vector<Command> cancelled;
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
      cancelled.swap(pending_);
    }
    for (Command& command : cancelled) {
      if (command.cancel) command.cancel();
    }
  }

 private:
  struct Command {
    SceneCommand run;
    std::function<void()> cancel;
  };
  mutable std::mutex mutex_;
  bool closed_ = false;
  std::vector<Command> pending_;
  std::vector<Command> running_;  ///< only touched by the physics thread
};

}  // namespace felt
