#include "net/io_pool.hpp"

#include <algorithm>
#include <string>
#include <thread>

#include "scheduling/thread_name.hpp"

namespace felt::net {

namespace asio = boost::asio;

IoPool::IoPool(unsigned threads) {
  for (unsigned t = 0; t < std::max(threads, 1u); ++t) {
    // one thread runs each: the hint lets the io_context skip waking other threads
    contexts_.push_back(std::make_unique<asio::io_context>(1));
  }
}

asio::io_context& IoPool::next() {
  return *contexts_[next_.fetch_add(1, std::memory_order_relaxed) % contexts_.size()];
}

void IoPool::run(const std::function<void()>& on_thread_start) {
  guards_.clear();
  std::vector<std::jthread> threads;
  for (std::size_t t = 1; t < contexts_.size(); ++t) {
    guards_.push_back(asio::make_work_guard(*contexts_[t]));
    threads.emplace_back([this, t, &on_thread_start] {
      on_thread_start();
      contexts_[t]->run();
    });
    // the first io_context runs on the process's main thread, which keeps the process's name
    name_thread(threads.back().native_handle(), "felt-net-" + std::to_string(t));
  }
  contexts_.front()->run();
  // the main io_context ran out of work or was stopped: so are the others
  stop();
}

void IoPool::stop() {
  for (const auto& context : contexts_) context->stop();
}

void IoPool::run_down() {
  guards_.clear();
  // a session closing on one io_context may post to another it has passed (an event to those in
  // its scene): again until a pass over all of them finds nothing to do
  std::size_t handled = 0;
  do {
    handled = 0;
    for (const auto& context : contexts_) {
      context->restart();
      handled += context->run();
    }
  } while (handled > 0);
}

}  // namespace felt::net
