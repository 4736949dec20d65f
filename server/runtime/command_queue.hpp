#pragma once
// Changes to a scene from other threads, applied by the physics thread between steps, never
// during one, in the order they were pushed. A command may have to wait for something made
// elsewhere (a reset for its rebuilt scene): until it is ready, it and every command after it
// wait while the scene steps on. A command that will never run (its scene stopped) is
// cancelled instead, so that whoever waits for it hears so. The physics thread sleeps in
// wait() between its steps; a push, or something a held-back command waits for being made
// (wake()), wakes it.

#include <condition_variable>
#include <functional>
#include <mutex>
#include <stop_token>
#include <vector>

#include "runtime/clock.hpp"
#include "scene/scene.hpp"

namespace felt {

using SceneCommand = std::function<void(Scene&)>;

class CommandQueue {
 public:
  /// Queues `run`; `cancel` is called instead if the queue is closed before it runs. `ready`
  /// (none: always) holds it and the later commands back while it is false. Returns false (and
  /// calls `cancel`) when the queue is already closed.
  bool push(SceneCommand run, std::function<void()> cancel = {}, std::function<bool()> ready = {}) {
    bool accepted = false;
    {
      std::lock_guard lock(mutex_);
      if (!closed_) {
        pending_.push_back({std::move(run), std::move(cancel), std::move(ready)});
        accepted = true;
      }
    }
    if (accepted) {
      wake();
      return true;
    }
    if (cancel) cancel();
    return false;
  }

  /// Wakes the physics thread to look at its commands: something a held-back command waits
  /// for is made.
  void wake() {
    // taking the lock orders what changed before the physics thread's look at the queue
    { std::lock_guard lock(wake_mutex_); }
    wake_.notify_all();
  }

  /// Sleeps until there is a command to run, `stop` is requested, or `clock` reaches `due`.
  /// Only for the thread that calls apply_all.
  void wait(Clock& clock, std::stop_token stop, Clock::time_point due) {
    std::unique_lock lock(wake_mutex_);
    clock.wait_until(lock, wake_, stop, due, [this] { return !idle(); });
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
  std::mutex wake_mutex_;
  std::condition_variable_any wake_;
};

}  // namespace felt
