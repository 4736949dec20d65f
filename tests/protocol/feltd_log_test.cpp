// feltd serve's log on standard error: a line for each client that comes and goes (with its name
// and address), each scene loaded, kept, destroyed or removed, each refusal of a limit, and the
// shutdown and its exit; --log-level chooses how much; nothing per haptic update.

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "client/scratch_directory.hpp"
#include "protocol/feltd_fixture.hpp"
#include "support/websocket_client.hpp"

namespace felt::test {
namespace {

/// Every line begins with the time in UTC to the millisecond and the level.
const std::string kStamp = R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z)";

class FeltdLogTest : public ::testing::Test {
 protected:
  /// Starts feltd with its standard error (the log) in log_path(): it inherits this process's
  /// standard error, which points there while it starts.
  void start(const std::vector<std::string>& args) {
    std::vector<std::string> all = default_args();
    all.insert(all.end(), args.begin(), args.end());
    const int log = open(log_path().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    ASSERT_GE(log, 0);
    std::fflush(stderr);
    const int saved = dup(STDERR_FILENO);
    dup2(log, STDERR_FILENO);
    close(log);
    try {
      server_ = std::make_unique<FeltdProcess>(all);
    } catch (...) {
      dup2(saved, STDERR_FILENO);
      close(saved);
      throw;
    }
    dup2(saved, STDERR_FILENO);
    close(saved);
  }
  void TearDown() override {
    if (server_ && server_->running()) {
      EXPECT_EQ(server_->stop(SIGTERM, 5s), 0);
    }
  }
  std::string log_path() const { return (dir_ / "feltd.log").string(); }
  std::vector<std::string> lines() const {
    std::ifstream in(log_path());
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  }
  /// A matched line ([0]) and its groups, copied: a std::smatch points into the line it
  /// matched, which the next look at the log frees (AddressSanitizer: heap-use-after-free).
  using Captures = std::vector<std::string>;
  /// The lines of `level` whose text matches `pattern`.
  std::vector<Captures> matching(const std::string& level, const std::string& pattern) {
    const std::regex line("^" + kStamp + " " + level + " +" + pattern + "$");
    log_ = lines();
    std::vector<Captures> found;
    for (const std::string& text : log_) {
      std::smatch match;
      if (std::regex_match(text, match, line)) found.emplace_back(match.begin(), match.end());
    }
    return found;
  }
  /// Waits for the first line of `level` matching `pattern`; fails the test without one (and
  /// returns no captures).
  Captures await_line(const std::string& level, const std::string& pattern) {
    const auto deadline = std::chrono::steady_clock::now() + scaled(10s);
    while (std::chrono::steady_clock::now() < deadline) {
      if (auto found = matching(level, pattern); !found.empty()) return found.front();
      std::this_thread::sleep_for(20ms);
    }
    std::string all;
    for (const std::string& line : log_) all += line + "\n";
    ADD_FAILURE() << "no " << level << " line " << pattern << " in:\n" << all;
    return {};
  }
  std::unique_ptr<Client> greeted(const std::string& name) {
    auto client = std::make_unique<Client>();
    client->connect("127.0.0.1", server_->port());
    client->set_reply_timeout(scaled(10s));
    client->hello(name);
    return client;
  }
  v1::SceneLoaded load(Client& client, bool keep) {
    v1::ClientMessage message;
    message.mutable_load_scene()->set_name("default");
    message.mutable_load_scene()->set_keep(keep);
    return client.request(message, v1::ServerMessage::kSceneLoaded).scene_loaded();
  }

  ScratchDirectory dir_;
  std::unique_ptr<FeltdProcess> server_;
  std::vector<std::string> log_;
};

TEST_F(FeltdLogTest, ClientsScenesAndTheShutdownAreLoggedOneLineEach) {
  start({});
  await_line("info", R"(scene 4294967296 "default" loaded from .*/default\.json, the scene new )"
                     R"(clients join)");
  auto alice = greeted("alice");
  const auto connected =
      await_line("info", R"(client (\d+) "alice" connected from 127\.0\.0\.1:(\d+) over TCP)");
  const std::string id = connected.at(1), port = connected.at(2);

  const std::string kept = std::to_string(load(*alice, true).scene_id());
  await_line("info", "client " + id + R"( "alice" loaded scene )" + kept + R"( "default", kept)");
  alice->destroy_scene(std::stoull(kept));
  await_line("info", "client " + id + R"( "alice" destroyed scene )" + kept + R"( "default")");
  const std::string loaded = std::to_string(load(*alice, false).scene_id());
  await_line("info", "client " + id + R"( "alice" loaded scene )" + loaded + R"( "default")");

  auto bob = greeted("bob");
  await_line("info", R"(client \d+ "bob" connected from 127\.0\.0\.1:\d+ over TCP)");
  // haptic updates are never logged
  const std::size_t before = lines().size();
  for (int k = 0; k < 200; ++k) bob->proxy_update(0, {0, 1.2, 0.01 * (k % 3)});
  EXPECT_EQ(lines().size(), before);

  alice->close();
  await_line("info", "scene " + loaded + R"( "default" removed: its last client left)");
  await_line("info", "client " + id + R"( "alice" from 127\.0\.0\.1:)" + port +
                         R"( over TCP left after 4 requests)");

  ASSERT_EQ(server_->stop(SIGTERM, 5s), 0);
  await_line("info", R"(shutting down on SIGTERM, 1 clients connected)");
  await_line("info", R"(client \d+ "bob" from 127\.0\.0\.1:\d+ over TCP left after 201 requests)");
  const auto all = lines();
  ASSERT_FALSE(all.empty());
  EXPECT_TRUE(std::regex_match(all.back(), std::regex("^" + kStamp +
                                                      R"( info +stopped, exit )"
                                                      R"(status 0$)")))
      << all.back();
  for (const std::string& line : all) {
    EXPECT_TRUE(
        std::regex_match(line, std::regex("^" + kStamp + R"( (error|warning|info) +\S.*$)")))
        << line;
  }
}

TEST_F(FeltdLogTest, AWebSocketClientIsNamedWithItsAddressToo) {
  start({"--web", "127.0.0.1:0"});
  WebSocketClient page;
  page.connect("127.0.0.1", server_->web_port());
  page.hello("page");
  await_line("info", R"(client \d+ "page" connected from 127\.0\.0\.1:\d+ over WebSocket)");
}

TEST_F(FeltdLogTest, RefusalsOfALimitAreWarningsAtMostOneASecondPerClient) {
  start({"--max-scenes", "1", "--max-clients", "2"});
  auto alice = greeted("alice\nforged line");  // a name cannot start a line of its own
  for (int k = 0; k < 3; ++k) {
    expect_error([&] { load(*alice, false); }, v1::ERROR_CODE_LIMIT_EXCEEDED);
  }
  const auto refused = await_line(
      "warning", R"(client (\d+) "alice\?forged line" from 127\.0\.0\.1:\d+ over TCP refused: )"
                 R"(the server already runs 1 scenes \(--max-scenes\) \(LIMIT_EXCEEDED\))");
  EXPECT_EQ(matching("warning", ".* refused: .*").size(), 1u);  // the next two within a second

  auto bob = greeted("bob");
  Client carol;  // a third client: one more than --max-clients
  carol.connect("127.0.0.1", server_->port());
  await_line("warning", R"(client \d+ from 127\.0\.0\.1:\d+ over TCP refused: the server )"
                        R"(already serves 2 clients \(--max-clients\) \(LIMIT_EXCEEDED\))");
  alice->close();
  await_line("info", "client " + refused.at(1) +
                         R"( "alice\?forged line" from .* left after 4 requests )"
                         R"(\(2 more refusals not logged\))");
}

TEST_F(FeltdLogTest, TheLogLevelChoosesWhatIsSaid) {
  start({"--log-level", "warning", "--max-scenes", "1"});
  {
    auto alice = greeted("alice");
    expect_error([&] { load(*alice, false); }, v1::ERROR_CODE_LIMIT_EXCEEDED);
    await_line("warning", R"(client \d+ "alice" from .* refused: .*)");
  }
  ASSERT_EQ(server_->stop(SIGTERM, 5s), 0);
  EXPECT_EQ(lines().size(), 1u);  // no client, scene or shutdown line

  start({"--log-level", "off", "--max-scenes", "1"});
  {
    auto alice = greeted("alice");
    expect_error([&] { load(*alice, false); }, v1::ERROR_CODE_LIMIT_EXCEEDED);
  }
  ASSERT_EQ(server_->stop(SIGTERM, 5s), 0);
  EXPECT_EQ(lines().size(), 0u);

  start({"--log-level", "debug"});
  {
    Client silent;  // connects and leaves without a Hello
    silent.connect("127.0.0.1", server_->port());
  }
  await_line("debug", R"(connection from 127\.0\.0\.1:\d+ over TCP)");
  await_line("debug", R"(connection from 127\.0\.0\.1:\d+ over TCP closed before Hello)");
}

}  // namespace
}  // namespace felt::test
