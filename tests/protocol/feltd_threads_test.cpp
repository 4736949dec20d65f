// feltd's threads seen from outside: the idle-core spinners run only while haptic updates come
// (and only when asked), and the threads off the haptic path take a higher nice than the network
// threads.

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "feltd_fixture.hpp"
#include "support/process_threads.hpp"

namespace felt::test {
namespace {

class FeltdSpinningTest : public FeltdTest {
 protected:
  std::vector<std::string> extra_args() const override { return {"--spin-idle-cores-ms", "20"}; }
};

TEST_F(FeltdSpinningTest, HapticUpdatesKeepIdleCoresAwakeUntilTheyStop) {
  const std::string pid = std::to_string(server_->pid());
  const SchedIdleThreads asleep = sched_idle_threads(pid);
  cpu_set_t cores;  // feltd has the cores this test may run on
  ASSERT_EQ(sched_getaffinity(0, sizeof cores, &cores), 0);
  EXPECT_EQ(asleep.count, CPU_COUNT(&cores));
  Client client;
  connect(client);
  client.hello("test");
  // the spinners take only idle cores: on a machine busy with other tests that may take a while
  const auto deadline = std::chrono::steady_clock::now() + scaled(20s);
  while (sched_idle_threads(pid).ticks == asleep.ticks &&
         std::chrono::steady_clock::now() < deadline) {
    client.proxy_update(0, {5, 5, 5});
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_GT(sched_idle_threads(pid).ticks, asleep.ticks) << "the idle cores never spun in 20 s";
  std::this_thread::sleep_for(100ms);  // past the linger
  const long stopped = sched_idle_threads(pid).ticks;
  std::this_thread::sleep_for(300ms);
  // a tick is 4 ms or 10 ms: spinning two cores would take 60 ticks or more
  EXPECT_LE(sched_idle_threads(pid).ticks - stopped, 2);
}

TEST_F(FeltdTest, IdleCoresSpinOnlyWhenAsked) {
  FeltdProcess spinning([] {
    std::vector<std::string> args = default_args();
    args.insert(args.end(), {"--spin-idle-cores-ms", "100"});
    return args;
  }());
  EXPECT_GT(sched_idle_threads(std::to_string(spinning.pid())).count, 0);
  EXPECT_EQ(sched_idle_threads(std::to_string(server_->pid())).count, 0);  // the default: off
}

/// The nices of `process`'s threads named `name`.
std::vector<int> nices_of(int process, const std::string& name) {
  std::vector<int> nices;
  for (const ThreadStat& thread : process_threads(std::to_string(process))) {
    if (thread.name == name) nices.push_back(thread.nice);
  }
  return nices;
}

TEST_F(FeltdTest, ThreadsOffTheHapticPathStepAsideForTheNetworkThreads) {
  auto client = greeted("loader");
  // a second scene, started from the loader thread, with a scripted device on a servo thread
  client->load_scene_by_name("finger_on_hammock");
  // feltd runs at the test's nice; a thread may raise its nice, not lower it
  const std::vector<int> network = nices_of(server_->pid(), "felt-net-1");
  ASSERT_EQ(network.size(), 1u);
  const int aside = std::max(network[0], 10);
  // a thread sets its nice as it starts, and its starter names it after starting it
  const auto settled = [&] {
    return nices_of(server_->pid(), "felt-physics") == std::vector<int>(2, aside) &&
           nices_of(server_->pid(), "felt-frames") == std::vector<int>(1, aside) &&
           nices_of(server_->pid(), "felt-servo").size() == 1;
  };
  const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
  while (!settled() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_EQ(nices_of(server_->pid(), "felt-physics"), std::vector<int>(2, aside));
  EXPECT_EQ(nices_of(server_->pid(), "felt-frames"), std::vector<int>(1, aside));
  for (const ThreadStat& thread : process_threads(std::to_string(server_->pid()))) {
    // the haptic path, and the loader, whose nice the scenes it starts would inherit
    if (thread.name.starts_with("felt-net") || thread.name == "feltd" ||
        thread.name == "felt-servo" || thread.name == "felt-loader") {
      EXPECT_EQ(thread.nice, network[0]) << thread.name;
    }
  }
  EXPECT_EQ(nices_of(server_->pid(), "felt-servo").size(), 1u);

  FeltdProcess as_the_network([] {
    std::vector<std::string> args = default_args();
    args.insert(args.end(), {"--background-nice", "0"});
    return args;
  }());
  EXPECT_EQ(nices_of(as_the_network.pid(), "felt-physics"), std::vector<int>(1, network[0]));
  EXPECT_EQ(nices_of(as_the_network.pid(), "felt-frames"), std::vector<int>(1, network[0]));
}

/// A server whose physics keeps up with the wall clock beside the other tests: at the default
/// nice 10, two test processes busy beside it left the cloth behind the finger's 1 kHz path (no
/// contact at the end of the press, or a finger held in a dent the cloth had not moved on from).

}  // namespace
}  // namespace felt::test
