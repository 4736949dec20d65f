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
  EXPECT_EQ(a.value() & 0xffffffffu, b.value() & 0xffffffffu);
  EXPECT_EQ(registry.find(a), nullptr);
  EXPECT_NE(registry.find(b), nullptr);
  EXPECT_EQ(registry.size(), 1u);
  EXPECT_EQ(registry.find(0), nullptr);
  EXPECT_EQ(registry.find(0xdeadbeef00000007ull), nullptr);
}

// A scene a client loads is its from the moment it is added: another client finds it, joins
// it, and may not control it, even before the loading client's session has joined.
TEST(SceneRegistry, ALoadedSceneHasItsOwnerAsAMemberFromTheStart) {
  SceneRegistry registry;
  constexpr ClientId kLoader = 7, kOther = 8;
  const SceneId id = registry.add(
      std::make_shared<SceneRunner>(Scene("mine", World()), SceneAccess{kLoader, false, false}),
      SceneMembers::Member{kLoader, {}, {}});
  const auto scene = registry.join(id, {kOther, "other", {}});
  ASSERT_NE(scene, nullptr);
  EXPECT_FALSE(scene->may_control(kOther));
  // the loader's session joining for real takes the place it had, it is not in twice
  registry.join(id, {kLoader, "loader", {}});
  EXPECT_EQ(scene->members().count(), 2u);
  EXPECT_FALSE(registry.leave(id, kLoader));  // the other is still in it
  EXPECT_TRUE(scene->may_control(kOther));    // its owner is gone: anyone's
  EXPECT_TRUE(registry.leave(id, kOther));    // the last one out: the scene goes
  EXPECT_EQ(registry.find(id), nullptr);
}

TEST(SceneRegistry, KeptScenesAreCountedPerOwner) {
  SceneRegistry registry;
  const auto runner = [](ClientId owner, bool keep) {
    return std::make_shared<SceneRunner>(Scene("s", World()), SceneAccess{owner, false, keep});
  };
  const SceneId kept = registry.add(runner(1, true));
  registry.add(runner(1, true));
  registry.add(runner(1, false));
  registry.add(runner(2, true));
  EXPECT_EQ(registry.kept_by(1), 2u);
  EXPECT_EQ(registry.kept_by(2), 1u);
  EXPECT_EQ(registry.kept_by(3), 0u);
  registry.remove(kept);
  EXPECT_EQ(registry.kept_by(1), 1u);
}

}  // namespace
}  // namespace felt
