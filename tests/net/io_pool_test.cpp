// The network threads' io_contexts: connections are dealt out in turn, each io_context is run
// by a thread of its own until stop(), and the run-down finishes what one posted to another.

#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "net/io_pool.hpp"

namespace felt::net {
namespace {

namespace asio = boost::asio;

TEST(IoPool, ConnectionsAreDealtOutInTurn) {
  IoPool pool(3);
  ASSERT_EQ(pool.size(), 3u);
  std::vector<asio::io_context*> dealt;
  for (int k = 0; k < 6; ++k) dealt.push_back(&pool.next());
  EXPECT_EQ(std::set<asio::io_context*>(dealt.begin(), dealt.begin() + 3).size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(dealt[k], dealt[k + 3]);
  EXPECT_EQ(IoPool(0).size(), 1u);  // a pool always has the main thread's
}

TEST(IoPool, EachIoContextRunsOnAThreadOfItsOwnUntilStopped) {
  IoPool pool(3);
  std::mutex mutex;
  std::set<std::thread::id> threads;
  int started = 0;
  // one handler on every io_context records its thread; the last one stops the pool
  std::vector<asio::io_context*> contexts{&pool.main()};
  for (int k = 0; k < 3; ++k) {
    asio::io_context& context = pool.next();
    if (&context != &pool.main()) contexts.push_back(&context);
  }
  for (asio::io_context* context : contexts) {
    asio::post(*context, [&] {
      std::lock_guard lock(mutex);
      threads.insert(std::this_thread::get_id());
      if (threads.size() == 3) pool.stop();
    });
  }
  // the main io_context has work until the pool stops: run() returns only through stop()
  asio::steady_timer keep_main(pool.main(), std::chrono::hours(1));
  keep_main.async_wait([](const boost::system::error_code&) {});
  pool.run([&] {
    std::lock_guard lock(mutex);
    ++started;
  });
  EXPECT_EQ(threads.size(), 3u);
  EXPECT_TRUE(threads.contains(std::this_thread::get_id()));  // the main one runs here
  EXPECT_EQ(started, 2);
  keep_main.cancel();
  pool.run_down();
}

TEST(IoPool, TheRunDownFinishesWhatOneIoContextPostedToAnother) {
  IoPool pool(2);
  pool.next();  // the first connection goes to the main thread, the second to the other
  asio::io_context& other = pool.next();
  ASSERT_NE(&other, &pool.main());
  asio::post(pool.main(), [&] { pool.stop(); });
  pool.run([] {});
  // as a closing session posts its goodbye to those in its scene on other threads
  bool relayed = false;
  // from the second io_context back to the first, which the run-down has passed by then
  asio::post(other, [&] { asio::post(pool.main(), [&] { relayed = true; }); });
  pool.run_down();
  EXPECT_TRUE(relayed);
}

}  // namespace
}  // namespace felt::net
