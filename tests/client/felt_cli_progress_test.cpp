// What felt shows while it works: a progress bar or a spinner on a terminal, nothing at all on
// a pipe.

#include "felt_cli_fixture.hpp"

namespace felt::test {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(FeltCliTest, ASingleLongRequestShowsASpinnerOnATerminalOnly) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> commands = {
      {{"load", "default"}, "loading default "},
      {{"stats", "--scene", "thesis/three_cubes"}, "loading thesis/three_cubes "},
      {{"add-cloth", "--grid", "5,5"}, "adding the body "},
      // the device commands' asynchronous client
      {{"record", "--scene", "default", "--path", "line", "--from", "0,1,1", "--to", "0,1,2",
        "--period", "0.05", "--out", (dir_ / "record.csv").string()},
       "loading default "}};
  for (const auto& [args, label] : commands) {
    SCOPED_TRACE(args[0]);
    const CommandResult shown = felt(args, StandardError::kTerminal);
    ASSERT_EQ(shown.status, 0) << shown.err;
    // the label, a spinner and the seconds waited, then the line cleared
    EXPECT_TRUE(
        std::regex_search(shown.err, std::regex(label + R"([|/\\-] \d+\.\d s\x1b\[K\r\x1b\[K)")))
        << shown.err;
    EXPECT_FALSE(contains(shown.out, "\x1b")) << shown.out;
    const CommandResult piped = felt(args);
    ASSERT_EQ(piped.status, 0) << piped.err;
    EXPECT_EQ(piped.err, "");
  }
}

TEST_F(FeltCliTest, CommandsThatCountToAnEndShowABarOnATerminal) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> commands = {
      {{"watch", "--frames", "3", "--out", dir_.path().string()}, "watch ["},
      {{"touch", "--path", "line", "--from", "0,1,1", "--to", "0,1,2", "--period", "0.2"},
       "touch ["},
      {{"bench-latency", "--seconds", "0.2", "--frame-rate", "0"}, "bench ["},
      {{"bench-floor", "--seconds", "0.2"}, "floor ["}};
  for (const auto& [args, label] : commands) {
    SCOPED_TRACE(args[0]);
    const CommandResult shown = felt(args, StandardError::kTerminal);
    ASSERT_EQ(shown.status, 0) << shown.err;
    EXPECT_TRUE(contains(shown.err, label)) << shown.err;
    EXPECT_TRUE(contains(shown.err, "==] 100%")) << shown.err;
    EXPECT_FALSE(contains(shown.out, "\x1b")) << shown.out;
  }
}

}  // namespace
}  // namespace felt::test
