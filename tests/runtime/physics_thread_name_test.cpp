// The runtime names the threads it starts, so that top -H, perf and a scheduler trace say which
// thread waited behind which.

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "runner_fixtures.hpp"
#include "runtime/scene_runner.hpp"

namespace felt {
namespace {

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
