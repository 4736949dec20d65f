#include "scene/scene_directory.hpp"

#include <fstream>

#include <gtest/gtest.h>

namespace felt {
namespace {

namespace fs = std::filesystem;

class SceneDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() /
            ("felt_scene_dir_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(base_);
    fs::create_directories(base_ / "scenes" / "thesis");
    std::ofstream(base_ / "scenes" / "default.json") << "{}";
    std::ofstream(base_ / "scenes" / "thesis" / "cubes.json") << "{}";
    std::ofstream(base_ / "secret.json") << "{}";
  }
  void TearDown() override { fs::remove_all(base_); }
  fs::path base_;
};

TEST_F(SceneDirectoryTest, ResolvesNamesInsideTheDirectory) {
  const SceneDirectory dir(base_ / "scenes");
  EXPECT_EQ(dir.resolve("default").value(), fs::canonical(base_ / "scenes" / "default.json"));
  EXPECT_EQ(dir.resolve("thesis/cubes").value(),
            fs::canonical(base_ / "scenes" / "thesis" / "cubes.json"));
  EXPECT_FALSE(dir.resolve("missing"));
}

TEST_F(SceneDirectoryTest, NoNameReachesOutside) {
  const SceneDirectory dir(base_ / "scenes");
  for (const char* name : {"../secret", "/etc/passwd", "thesis/../../secret", "", "a//b", ".", "..",
                           "thesis/", "default.json", "de fault", "~/x"}) {
    EXPECT_FALSE(dir.resolve(name)) << name;
  }
  // a link inside the directory that points out of it is refused too
  fs::create_symlink(base_ / "secret.json", base_ / "scenes" / "linked.json");
  EXPECT_FALSE(dir.resolve("linked"));
}

}  // namespace
}  // namespace felt
