#pragma once
// Changes to a scene from other threads, applied by the physics thread between steps, never
// during one, in the order they were pushed. A command may have to wait for something made
// elsewhere (a reset for its rebuilt scene): until it is ready, it and every command after it
// wait while the scene steps on. A command that will never run (its scene stopped) is
// cancelled instead, so that whoever waits for it hears so.

#include <functional>
#include <mutex>
#include <vector>

#include "scene/scene.hpp"

namespace felt {

using SceneCommand = std::function<void(Scene&)>;

class CommandQueue {
 public:
  /// Queues `run`; `cancel` is called instead if the queue is closed before it runs. `ready`
  /// (none: always) holds it and the later commands back while it is false. Returns false (and
  /// calls `cancel`) when the queue is already closed.
  bool push(SceneCommand run, std::function<void()> cancel = {}, std::function<bool()> ready = {}) {
    {
      std::lock_guard lock(mutex_);
      if (!closed_) {
        pending_.push_back({std::move(run), std::move(cancel), std::move(ready)});
        return true;
      }
    }
    if (cancel) cancel();
    return false;
  }

  /// Runs the queued commands on `scene`, in order, up to the first that is not ready.
  void apply_all(Scene& scene) {
    {
      std::lock_guard lock(mutex_);
      for (Command& command : pending_) waiting_.push_back(std::move(command));
      pending_.clear();
    }
    std::size_t done = 0;
    for (; done < waiting_.size(); ++done) {
      const Command& command = waiting_[done];
      if (command.ready && !command.ready()) break;
      command.run(scene);
    }
    waiting_.erase(waiting_.begin(), waiting_.begin() + static_cast<std::ptrdiff_t>(done));
  }

  /// Whether apply_all has nothing to run: nothing queued since, and the first held-back
  /// command (if any) still not ready. Only for the thread that calls apply_all.
  bool idle() const {
    {
      std::lock_guard lock(mutex_);
      if (!pending_.empty()) return false;
    }
    return waiting_.empty() || (waiting_.front().ready && !waiting_.front().ready());
  }

  /// Cancels what is queued or held back and every later push. Call it once apply_all can no
  /// longer run (the physics thread has stopped).
  void close() {
    std::vector<Command> cancelled;
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
      cancelled.swap(waiting_);
      for (Command& command : pending_) cancelled.push_back(std::move(command));
      pending_.clear();
    }
    for (Command& command : cancelled) {
      if (command.cancel) command.cancel();
    }
  }

 private:
  struct Command {
    SceneCommand run;
    std::function<void()> cancel;
    std::function<bool()> ready;
  };
  mutable std::mutex mutex_;
  bool closed_ = false;
  std::vector<Command> pending_;
  std::vector<Command> waiting_;  ///< taken from pending_; only touched by the physics thread
};

}  // namespace felt
