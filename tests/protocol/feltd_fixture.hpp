#pragma once
// What the end-to-end tests share: the real feltd on port 0 serving the default scene, and
// small checks.

#include <signal.h>

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "felt_client.hpp"
#include "feltd_process.hpp"
#include "support/time_scale.hpp"

namespace felt::test {

namespace v1 = felt::v1;
using client::Client;
using client::ClientError;
using namespace std::chrono_literals;

inline std::vector<std::string> default_args() {
  return {"--scene-dir", FELT_SCENE_DIR, "--scene", std::string(FELT_SCENE_DIR) + "/default.json"};
}

/// A feltd serving the default scene; tests that need other flags override extra_args().
class FeltdTest : public ::testing::Test {
 protected:
  virtual std::vector<std::string> extra_args() const { return {}; }
  void SetUp() override {
    std::vector<std::string> args = default_args();
    for (std::string& arg : extra_args()) args.push_back(std::move(arg));
    server_ = std::make_unique<FeltdProcess>(args);
  }
  void TearDown() override {
    if (server_ && server_->running()) {
      EXPECT_EQ(server_->stop(SIGTERM, 5s), 0);
    }
  }
  /// Connects `client`, which then waits for a reply as long as a sanitized build needs.
  void connect(Client& client) {
    client.connect("127.0.0.1", server_->port());
    client.set_reply_timeout(scaled(10s));
  }
  /// A connected client that has said hello as `name`.
  std::unique_ptr<Client> greeted(const std::string& name) {
    auto client = std::make_unique<Client>();
    connect(*client);
    client->hello(name);
    return client;
  }

  std::unique_ptr<FeltdProcess> server_;
};

/// A feltd whose physics and frame encoder run at the network threads' priority, for tests that
/// need the scene to keep its pace beside the rest of the suite: niced, a loaded machine starved
/// a 100 x 100 cloth to a few published frames in 30 s.
class FeltdUnnicedTest : public FeltdTest {
 protected:
  std::vector<std::string> extra_args() const override { return {"--background-nice", "0"}; }
};

/// Polls `done` every 5 ms until it holds or `timeout` (scaled) has passed: whether it held.
template <typename Predicate>
bool eventually(Predicate done, std::chrono::milliseconds timeout = 5s) {
  const auto deadline = std::chrono::steady_clock::now() + scaled(timeout);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

/// Runs `call` and expects it to throw the server's error `code`, whose message says `says`.
template <typename Call>
void expect_error(Call call, v1::ErrorCode code, const std::string& says = "") {
  try {
    call();
    ADD_FAILURE() << "no error (expected code " << code << ")";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

inline std::array<double, 3> vertex(const v1::BodyFrame& body, int v) {
  return {body.positions(3 * v), body.positions(3 * v + 1), body.positions(3 * v + 2)};
}

/// Sends `requests` StepScene requests of `steps` steps each without waiting; their ids.
inline std::vector<std::uint64_t> send_steps(Client& client, int requests, std::uint32_t steps) {
  std::vector<std::uint64_t> ids;
  for (int i = 0; i < requests; ++i) {
    v1::ClientMessage step;
    step.mutable_step_scene()->set_steps(steps);
    ids.push_back(client.send(step));
  }
  return ids;
}

/// A small hanging cloth as AddBody takes it.
inline std::string small_cloth_json(double x = 2.0) {
  return R"({"type": "cloth", "name": "flag", "grid": {"nx": 6, "ny": 6, "width": 0.5,
             "height": 0.5, "center": [)" +
         std::to_string(x) + R"(, 1.5, 0]}, "pin": "top_corners"})";
}

/// Whether `message` tells of a step its scene rescued with substeps or cut short at its budget:
/// news of the scene's health, which a test of something else leaves out.
inline bool tells_of_a_rescue(const v1::ServerMessage& message) {
  return message.has_event() && (message.event().kind() == v1::EVENT_KIND_STEP_RESCUED ||
                                 message.event().kind() == v1::EVENT_KIND_STEP_OVER_BUDGET);
}

/// The messages as text, one a line: what a test names when it got other messages than it expected.
inline std::string describe(const std::vector<v1::ServerMessage>& messages) {
  std::string text;
  for (const v1::ServerMessage& message : messages) text += message.ShortDebugString() + "\n";
  return text;
}

}  // namespace felt::test
