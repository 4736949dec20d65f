#include "scheduling/thread_name.hpp"

#include <pthread.h>

#include <array>
#include <string>
#include <thread>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace felt
