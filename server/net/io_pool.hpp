#pragma once
// The network's threads, each running an io_context of its own. A connection is given to one
// of them when it is accepted and is served wholly by that thread: the thread epoll wakes for a
// haptic update is the one that answers it. With one io_context shared by all the threads, the
// waking thread often handed the completion to another through the io_context's condition
// variable: two wake-ups per update instead of one, and each a chance to wait for a core
// (docs/results/service.md).

#include <atomic>
#include <functional>
#include <memory>
#include <vector>

#include <boost/asio.hpp>

namespace felt::net {

class IoPool {
 public:
  /// `threads` io_contexts (at least one), the first run by the thread that calls run().
  explicit IoPool(unsigned threads);

  /// The io_context of the calling thread's run(): the daemon's own timers and signals.
  boost::asio::io_context& main() { return *contexts_.front(); }
  /// The io_context the next connection is served on, in turn (thread-safe).
  boost::asio::io_context& next();
  std::size_t size() const { return contexts_.size(); }

  /// Runs the first io_context on the calling thread and each other one on a thread of its
  /// own, which first calls `on_thread_start`; returns once stop() was called and every thread
  /// has returned.
  void run(const std::function<void()>& on_thread_start);
  /// Makes run() return (from any thread).
  void stop();
  /// After run(): runs every io_context on the calling thread until none has anything left,
  /// so that what the sessions still had to do ends before the io_contexts are destroyed.
  void run_down();

 private:
  using WorkGuard = boost::asio::executor_work_guard<boost::asio::io_context::executor_type>;

  std::vector<std::unique_ptr<boost::asio::io_context>> contexts_;
  std::vector<WorkGuard> guards_;  ///< keep the other threads running while they serve nobody
  std::atomic<std::size_t> next_{0};
};

}  // namespace felt::net
