// felt pause, resume, step, reset, save, restore and destroy as a user types them, against
// feltd serving the default scene (a 20 x 20 curtain that swings from its start).

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "felt_cli_fixture.hpp"

namespace felt::test {
namespace {

/// The step a status line `felt` printed for the default scene names, or -1.
double status_step(const std::string& out, const std::string& state) {
  const auto n = numbers_in(
      out, R"(^scene 4294967296: step (\d+), t [0-9.]+ s, )" + state + R"(, time scale 1\n$)");
  return n.empty() ? -1 : n[0];
}

TEST_F(FeltCliTest, PauseStepAndResumeDriveTheScenesClock) {
  const CommandResult running = felt({"step", "10"});
  EXPECT_EQ(running.status, 1);
  EXPECT_EQ(running.err, "felt: the scene is running; pause it first (WRONG_STATE)\n");

  const CommandResult paused = felt({"pause"});
  ASSERT_EQ(paused.status, 0) << paused.err;
  const double at = status_step(paused.out, "paused");
  ASSERT_GE(at, 0) << paused.out;
  const CommandResult stepped = felt({"step", "250"});
  ASSERT_EQ(stepped.status, 0) << stepped.err;
  EXPECT_EQ(status_step(stepped.out, "paused"), at + 250) << stepped.out;
  // the clock stays where the steps left it (a pause of a paused scene changes nothing)
  EXPECT_EQ(status_step(felt({"pause"}).out, "paused"), at + 250);
  const CommandResult stats = felt({"stats"});
  EXPECT_NE(stats.out.find(", paused, time scale 1\n"), std::string::npos) << stats.out;

  const CommandResult resumed = felt({"resume"});
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_GE(status_step(resumed.out, "running"), at + 250) << resumed.out;
  EXPECT_EQ(felt({"step", "0"}).err, "felt: steps must be 1 to 100000 (BAD_REQUEST)\n");
}

TEST_F(FeltCliTest, SaveAndRestoreBringTheCurtainBackWhereItWas) {
  ASSERT_EQ(felt({"pause"}).status, 0);
  const std::string file = (dir_ / "state.json").string();
  const CommandResult saved = felt({"save", file});
  ASSERT_EQ(saved.status, 0) << saved.err;
  const auto save_line = numbers_in(
      saved.out, "^state (\\d+) saved to " + file + R"(: step (\d+), t [0-9.]+ s, 1 bodies\n$)");
  ASSERT_EQ(save_line.size(), 2u) << saved.out;
  const double at = save_line[1];
  // the file is the scene's state, readable as JSON: 400 particles of the one cloth
  const nlohmann::json state = nlohmann::json::parse(std::ifstream(file));
  ASSERT_EQ(state["bodies"].size(), 1u);
  const std::vector<double> positions = state["bodies"][0]["positions"];
  ASSERT_EQ(positions.size(), 3u * 400);
  EXPECT_EQ(state["bodies"][0]["velocities"].size(), 3u * 400);

  auto watcher = greeted("watcher");
  watcher->subscribe_frames(60);
  const CommandResult stepped = felt({"step", "300"});
  ASSERT_EQ(status_step(stepped.out, "paused"), at + 300) << stepped.out << stepped.err;
  std::optional<v1::Frame> later;
  do {
    later = watcher->next_frame(scaled(5s));
    ASSERT_TRUE(later);
  } while (later->step() < at + 300);

  const CommandResult restored = felt({"restore", file});
  ASSERT_EQ(restored.status, 0) << restored.err;
  EXPECT_EQ(status_step(restored.out, "paused"), at) << restored.out;
  std::optional<v1::Frame> back;
  do {
    back = watcher->next_frame(scaled(5s));
    ASSERT_TRUE(back);
  } while (back->step() != at);
  double moved = 0, off = 0;  // the 300 steps moved the curtain; the restore put it back
  for (int v = 0; v < 400; ++v) {
    const auto a = vertex(later->bodies(0), v), b = vertex(back->bodies(0), v);
    moved = std::max(moved, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    off = std::max(off, std::hypot(b[0] - positions[3 * v], b[1] - positions[3 * v + 1],
                                   b[2] - positions[3 * v + 2]));
  }
  EXPECT_GT(moved, 1e-3);
  EXPECT_LT(off, 1e-6);  // frames carry float32
}

TEST_F(FeltCliTest, RestoreRefusesWhatIsNoSavedStateOfThisScene) {
  const std::string missing = (dir_ / "missing.json").string();
  const CommandResult none = felt({"restore", missing});
  EXPECT_EQ(none.status, 2);
  EXPECT_EQ(none.err, "felt: cannot read " + missing + "\n");

  const std::string garbage = (dir_ / "garbage.json").string();
  std::ofstream(garbage) << "{\"bodies\": 3";
  const CommandResult bad = felt({"restore", garbage});
  EXPECT_EQ(bad.status, 2);
  EXPECT_TRUE(bad.err.starts_with("felt: " + garbage + " is no state 'felt save' wrote: "))
      << bad.err;
  EXPECT_EQ(bad.err.find("(BAD_REQUEST)"), std::string::npos) << bad.err;

  // a state, but of a cloth of 2 particles: the server refuses it
  const std::string other = (dir_ / "other.json").string();
  std::ofstream(other) << R"({"bodies": [{"body_id": 0, "positions": [0, 0, 0, 1, 0, 0],
                                          "velocities": [0, 0, 0, 0, 0, 0]}]})";
  const CommandResult refused = felt({"restore", other});
  EXPECT_EQ(refused.status, 1);
  EXPECT_TRUE(refused.err.ends_with(" (BAD_REQUEST)\n")) << refused.err;
}

TEST_F(FeltCliTest, ResetTakesTheSceneBackToItsFile) {
  ASSERT_EQ(felt({"pause"}).status, 0);
  ASSERT_EQ(felt({"add-cloth", "--grid", "10,10", "--center", "0,1,0.5"}).status, 0);
  ASSERT_EQ(felt({"step", "20"}).status, 0);
  EXPECT_NE(felt({"stats"}).out.find(" 2 bodies, 500 particles"), std::string::npos);
  const CommandResult reset = felt({"reset"});
  ASSERT_EQ(reset.status, 0) << reset.err;
  EXPECT_EQ(reset.out, "scene 4294967296: step 0, t 0.000 s, paused, time scale 1\n");
  EXPECT_NE(felt({"stats"}).out.find(" 1 bodies, 400 particles"), std::string::npos);
}

TEST_F(FeltCliTest, DestroyStopsALoadedSceneButNotTheServersOwn) {
  const CommandResult loaded = felt({"load", "default"});
  const auto id = numbers_in(loaded.out, R"(^scene (\d+) "default")");
  ASSERT_EQ(id.size(), 1u) << loaded.out << loaded.err;
  const std::string scene = std::to_string(static_cast<std::uint64_t>(id[0]));
  // the client that loaded it is gone, so anyone controls it
  const CommandResult paused = felt({"pause", "--join", scene});
  EXPECT_EQ(paused.status, 0) << paused.err;
  EXPECT_TRUE(paused.out.starts_with("scene " + scene + ": step ")) << paused.out;
  EXPECT_TRUE(paused.out.ends_with(", paused, time scale 1\n")) << paused.out;

  const CommandResult destroyed = felt({"destroy", scene});
  ASSERT_EQ(destroyed.status, 0) << destroyed.err;
  EXPECT_EQ(destroyed.out, "scene " + scene + " destroyed\n");
  EXPECT_EQ(felt({"scenes"}).out.find("\n  " + scene + "  "), std::string::npos);
  const CommandResult again = felt({"destroy", scene});
  EXPECT_EQ(again.status, 1);
  EXPECT_TRUE(again.err.ends_with(" (UNKNOWN_ID)\n")) << again.err;

  const CommandResult own = felt({"destroy", "4294967296"});
  EXPECT_EQ(own.status, 1);
  EXPECT_EQ(own.err, "felt: the server's own scenes cannot be destroyed (PERMISSION_DENIED)\n");
  EXPECT_EQ(felt({"stats"}).status, 0);
}

}  // namespace
}  // namespace felt::test
