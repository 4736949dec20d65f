#include "scheduling/thread_name.hpp"

#include <pthread.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "runner_fixtures.hpp"
#include "runtime/scene_runner.hpp"

namespace felt {
namespace {

std::string name_of(pthread_t thread) {
  std::array<char, 64> name{};
  EXPECT_EQ(pthread_getname_np(thread, name.data(), name.size()), 0);
  return name.data();
}

TEST(ThreadName, ANameIsCutToTheKernelsFifteenCharacters) {
  std::jthread thread([](std::stop_token stop) {
    while (!stop.stop_requested()) std::this_thread::yield();
  });
  ASSERT_TRUE(name_thread(thread.native_handle(), "felt-net-1"));
  EXPECT_EQ(name_of(thread.native_handle()), "felt-net-1");
  ASSERT_TRUE(name_thread(thread.native_handle(), "felt-a-name-longer-than-fifteen"));
  EXPECT_EQ(name_of(thread.native_handle()), "felt-a-name-lon");
}

TEST(ThreadName, AScenesPhysicsThreadIsNamedForATrace) {
  SceneRunner runner(flat_cloth_scene());
  runner.start();
  bool found = false;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    std::getline(comm, name);
    found = found || name == "felt-physics";
  }
  runner.stop();
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace felt
