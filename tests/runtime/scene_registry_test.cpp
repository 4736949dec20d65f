#include "runtime/scene_registry.hpp"

#include <gtest/gtest.h>

namespace felt {
namespace {

std::shared_ptr<SceneRunner> empty_runner() {
  return std::make_shared<SceneRunner>(Scene("empty", World()));
}

TEST(SceneRegistry, StaleIdsAreNeverReused) {
  SceneRegistry registry;
  const SceneId a = registry.add(empty_runner());
  EXPECT_NE(a, 0u);
  EXPECT_NE(registry.find(a), nullptr);
  EXPECT_TRUE(registry.remove(a));
  EXPECT_EQ(registry.find(a), nullptr);
  EXPECT_FALSE(registry.remove(a));

  // the slot is reused with a new generation: the old id still finds nothing
  const SceneId b = registry.add(empty_runner());
  EXPECT_NE(a, b);
  EXPECT_EQ(a & 0xffffffffu, b & 0xffffffffu);
  EXPECT_EQ(registry.find(a), nullptr);
  EXPECT_NE(registry.find(b), nullptr);
  EXPECT_EQ(registry.size(), 1u);
  EXPECT_EQ(registry.find(0), nullptr);
  EXPECT_EQ(registry.find(0xdeadbeef00000007ull), nullptr);
}

}  // namespace
}  // namespace felt
