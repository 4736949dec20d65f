// felt hello, scenes, load, stats and the body commands (add-cloth, add-solid, set, pin) as a
// user types them, against feltd serving the default scene.

#include "felt_cli_fixture.hpp"

namespace felt::test {
namespace {

TEST_F(FeltCliTest, HelloPrintsTheServersVersionCapabilitiesAndLimits) {
  const CommandResult r = felt({"hello"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(^feltd 0\.1\.0, protocol 1, client \d+, )"
                                                  R"(scene 4294967296\n)")))
      << r.out;
  EXPECT_NE(r.out.find(" haptics.proxy "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("limits: 64 clients, 32 scenes, 256 bodies and 250000 particles per "
                       "scene, 16 proxies, 16 requests in flight"),
            std::string::npos)
      << r.out;
}

TEST_F(FeltCliTest, ScenesListsTheFilesAndWhatRuns) {
  const CommandResult r = felt({"scenes"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("scene files:\n"), std::string::npos);
  EXPECT_NE(r.out.find("\n  default\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  thesis/three_cubes\n"), std::string::npos) << r.out;
  EXPECT_TRUE(std::regex_search(
      r.out, std::regex(R"(running:\n  4294967296  default +1 clients +1 bodies .* shared  kept)")))
      << r.out;
}

TEST_F(FeltCliTest, ALoadedSceneStaysForOthersToJoin) {
  const CommandResult loaded = felt({"load", "thesis/three_cubes"});
  ASSERT_EQ(loaded.status, 0) << loaded.err;
  const auto id = numbers_in(loaded.out, R"(^scene (\d+) "three_cubes", time step 0\.01 s\n)");
  ASSERT_EQ(id.size(), 1u) << loaded.out;
  EXPECT_TRUE(std::regex_search(loaded.out, std::regex(R"(body 2  solid +top +2402 vertices)")))
      << loaded.out;
  const std::string scene = std::to_string(static_cast<std::uint64_t>(id[0]));
  // the loading client is gone, and its scene still runs, not shared
  const CommandResult scenes = felt({"scenes"});
  EXPECT_TRUE(std::regex_search(
      scenes.out, std::regex("\n  " + scene + R"(  three_cubes +0 clients +4 bodies .*  kept\n)")))
      << scenes.out;
  const CommandResult stats = felt({"stats", "--join", scene});
  ASSERT_EQ(stats.status, 0) << stats.err;
  EXPECT_NE(stats.out.find("scene " + scene + ": step"), std::string::npos) << stats.out;
  EXPECT_NE(stats.out.find("  1 clients, 4 bodies, 7206 particles"), std::string::npos)
      << stats.out;
}

TEST_F(FeltCliTest, ASharedSceneLetsAnyoneWhoJoinsChangeIt) {
  const CommandResult loaded = felt({"load", "default", "--shared"});
  ASSERT_EQ(loaded.status, 0) << loaded.err;
  const auto id = numbers_in(loaded.out, R"(^scene (\d+) "default", shared,)");
  ASSERT_EQ(id.size(), 1u) << loaded.out;
  const std::string scene = std::to_string(static_cast<std::uint64_t>(id[0]));
  const CommandResult set = felt({"set", "--join", scene, "--body", "0", "--structural", "300"});
  EXPECT_EQ(set.status, 0) << set.err;
  EXPECT_EQ(set.out, "body 0 updated\n");
  EXPECT_TRUE(std::regex_search(felt({"scenes"}).out,
                                std::regex("\n  " + scene + R"(  default .*  shared  kept\n)")));
}

TEST_F(FeltCliTest, LoadingAMissingSceneSaysWhyAndFails) {
  const CommandResult r = felt({"load", "nope"});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "felt: no scene \"nope\" (NOT_FOUND)\n");
  EXPECT_EQ(r.out, "");
}

TEST_F(FeltCliTest, AddedBodiesAreCountedByStats) {
  const CommandResult cloth = felt({"add-cloth", "--grid", "10,10", "--center", "0,1,0.5"});
  ASSERT_EQ(cloth.status, 0) << cloth.err;
  EXPECT_EQ(cloth.out, "body 1: cloth \"cloth1\", 100 vertices, 162 triangles\n");
  const CommandResult solid = felt({"add-solid", "--name", "box", "--center", "0,0.5,0.5"});
  ASSERT_EQ(solid.status, 0) << solid.err;
  // a 3 x 3 x 3 lattice: the 4^3 - 2^3 nodes on its surface, 6 faces of 9 squares
  EXPECT_EQ(solid.out, "body 2: solid \"box\", 56 vertices, 108 triangles\n");
  const CommandResult stats = felt({"stats"});
  ASSERT_EQ(stats.status, 0) << stats.err;
  EXPECT_NE(stats.out.find("  1 clients, 3 bodies, 556 particles"), std::string::npos) << stats.out;
  EXPECT_TRUE(
      std::regex_search(stats.out, std::regex(R"(^scene 4294967296: step \d+, t [0-9.]+ s)")))
      << stats.out;
  EXPECT_TRUE(std::regex_search(stats.out, std::regex(R"(\nserver: 1 clients, 1 scenes, up )")))
      << stats.out;
}

TEST_F(FeltCliTest, ABodyTheServerRefusesIsNotAdded) {
  const CommandResult r = felt({"add-cloth", "--grid", "1,1"});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "felt: body.grid.nx: must be between 2 and 2048 (BAD_SCENE)\n");
  EXPECT_NE(felt({"stats"}).out.find(" 1 bodies, 400 particles"), std::string::npos);
}

TEST_F(FeltCliTest, SetChangesABodyAndRefusesWhatIsWrong) {
  const CommandResult r =
      felt({"set", "--body", "0", "--integrator", "implicit_euler", "--structural", "2000"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "body 0 updated\n");
  const CommandResult bad = felt({"set", "--body", "0", "--integrator", "nope"});
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(bad.err, "felt: unknown integrator \"nope\" (BAD_REQUEST)\n");
  const CommandResult missing = felt({"set", "--body", "5", "--drag", "1"});
  EXPECT_EQ(missing.status, 1);
  EXPECT_EQ(missing.err, "felt: no body 5 in this scene (UNKNOWN_ID)\n");
}

TEST_F(FeltCliTest, APinnedParticleStaysWhereItIs) {
  const CommandResult r = felt({"pin", "--body", "0", "--pin", "399"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "body 0: 1 pinned, 0 freed\n");
  // watch the curtain, which still swings from its start, for a while
  auto watcher = greeted("watcher");
  watcher->subscribe_frames(60);
  ASSERT_TRUE(watcher->next_frame(scaled(5s)));  // may show the step before the pin
  const auto first = watcher->next_frame(scaled(5s));
  ASSERT_TRUE(first);
  std::optional<v1::Frame> last;
  do {
    last = watcher->next_frame(scaled(5s));
    ASSERT_TRUE(last);
  } while (last->step() < first->step() + 300);  // 0.3 s later
  EXPECT_EQ(vertex(last->bodies(0), 399), vertex(first->bodies(0), 399));
  double moved = 0;  // the largest move of any other vertex
  for (int v = 0; v < 399; ++v) {
    const auto a = vertex(first->bodies(0), v), b = vertex(last->bodies(0), v);
    moved = std::max(moved, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
  }
  EXPECT_GT(moved, 1e-4);
  EXPECT_EQ(felt({"pin", "--body", "0", "--pin", "400"}).err,
            "felt: particle 400 out of range (the body has 400) (BAD_REQUEST)\n");
}

}  // namespace
}  // namespace felt::test
