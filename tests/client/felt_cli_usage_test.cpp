// felt's and feltd's command lines themselves: --server after the command's name or from
// FELT_SERVER, --version, and usage errors (exit status 2, never labelled with a server error
// code), against feltd serving the default scene.

#include <cstdlib>

#include "felt_cli_fixture.hpp"

namespace felt::test {
namespace {

/// Sets an environment variable for the commands a test runs, and unsets it after.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const std::string& value) : name_(name) {
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnvironment() { unsetenv(name_); }

 private:
  const char* name_;
};

class FeltCommandLineTest : public FeltCliTest {
 protected:
  std::string address() const { return "127.0.0.1:" + std::to_string(server_->port()); }
};

TEST_F(FeltCommandLineTest, TheServerMayComeAfterTheCommandsName) {
  const CommandResult r = run_command({FELT_PATH, "stats", "--server", address()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.out.starts_with("scene 4294967296: step ")) << r.out;
  const CommandResult pause = run_command({FELT_PATH, "pause", "--server", address()});
  EXPECT_EQ(pause.status, 0) << pause.err;
}

TEST_F(FeltCommandLineTest, FeltServerNamesTheServerUnlessTheCommandLineDoes) {
  {
    const ScopedEnvironment env("FELT_SERVER", address());
    const CommandResult r = run_command({FELT_PATH, "hello"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.out.starts_with("feltd 0.1.0, protocol 1, ")) << r.out;
  }
  // nothing listens on port 1: the command line's --server is the one used
  const ScopedEnvironment env("FELT_SERVER", "127.0.0.1:1");
  EXPECT_EQ(run_command({FELT_PATH, "hello", "--server", address()}).status, 0);
  const CommandResult refused = run_command({FELT_PATH, "hello"});
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find("127.0.0.1:1"), std::string::npos) << refused.err;
}

TEST_F(FeltCommandLineTest, BothProgramsSayTheirVersion) {
  const CommandResult felt_version = run_command({FELT_PATH, "--version"});
  EXPECT_EQ(felt_version.status, 0);
  EXPECT_EQ(felt_version.out, "felt 0.1.0\n");
  const CommandResult feltd_version = run_command({FELTD_PATH, "--version"});
  EXPECT_EQ(feltd_version.status, 0);
  EXPECT_EQ(feltd_version.out, "feltd 0.1.0\n");
  // the server a client talks to says the same
  EXPECT_TRUE(felt({"hello"}).out.starts_with("feltd 0.1.0, "));
}

TEST_F(FeltCommandLineTest, UsageErrorsExitWithTwoAndNoServerCode) {
  const std::vector<std::vector<std::string>> wrong = {
      {FELT_PATH},                                  // no command
      {FELT_PATH, "stats", "--no-such-option"},     // unknown option
      {FELT_PATH, "destroy"},                       // no scene id
      {FELT_PATH, "step", "many"},                  // not a number
      {FELT_PATH, "--server", "nowhere", "hello"},  // no HOST:PORT
      {FELT_PATH, "touch", "--path", "spiral"},     // no such path
      {FELT_PATH, "touch", "--path", "line"},       // without --from and --to
      {FELT_PATH, "add-cloth", "--json", "@/nonexistent/cloth.json"},
      {FELT_PATH, "restore", "/nonexistent/state.json"},
      {FELTD_PATH},
      {FELTD_PATH, "serve", "--no-such-option"},
      {FELTD_PATH, "serve", "--listen", "nowhere"},
      {FELTD_PATH, "serve", "--log-level", "chatty"},
  };
  for (const auto& argv : wrong) {
    std::vector<std::string> args = argv;
    if (argv[0] == FELT_PATH && argv.size() > 1 && argv[1] != "--server") {
      args.insert(args.begin() + 1, {"--server", address()});
    }
    const CommandResult r = run_command(args);
    std::string line;
    for (const std::string& arg : argv) line += arg + " ";
    EXPECT_EQ(r.status, 2) << line << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << line;
    EXPECT_EQ(r.out, "") << line;
    EXPECT_FALSE(std::regex_search(r.err, std::regex(R"(\([A-Z_]+\)\n$)"))) << line << r.err;
  }
  EXPECT_EQ(run_command({FELT_PATH, "--server", "nowhere", "hello"}).err.substr(0, 16),
            "felt: --server: ");
  EXPECT_EQ(run_command({FELT_PATH, "--server", address(), "touch", "--path", "spiral"}).err,
            "felt: --path must be line, circle, press or csv\n");
}

}  // namespace
}  // namespace felt::test
