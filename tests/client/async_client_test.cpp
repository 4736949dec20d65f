// The asynchronous client (what felt's device loops run on) against the real feltd on port 0:
// stamped forces, many updates in flight from several threads, replies routed by id, errors,
// and connections that end while requests wait.

#include <signal.h>

#include <cmath>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <set>
#include <thread>

#include "async_client.hpp"
#include "protocol/feltd_fixture.hpp"

namespace felt::test {
namespace {

using client::AsyncClient;
using Clock = std::chrono::steady_clock;

/// What a client's handlers were given, for the test's thread to wait on.
template <class T>
class Inbox {
 public:
  void put(const T& item) {
    std::lock_guard lock(mutex_);
    items_.push_back(item);
    arrived_.notify_all();
  }
  /// Waits until `count` items came (true) or `timeout` passed; then returns what came.
  bool wait_for(std::size_t count, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    return arrived_.wait_for(lock, timeout, [&] { return items_.size() >= count; });
  }
  std::vector<T> items() {
    std::lock_guard lock(mutex_);
    return items_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<T> items_;
};

v1::ClientMessage proxy_update(std::uint32_t proxy, const std::array<double, 3>& at,
                               std::uint64_t stamp) {
  v1::ClientMessage message;
  v1::ProxyUpdate& update = *message.mutable_proxy_update();
  update.set_proxy_id(proxy);
  update.mutable_position()->set_x(at[0]);
  update.mutable_position()->set_y(at[1]);
  update.mutable_position()->set_z(at[2]);
  update.set_client_time_us(stamp);
  return message;
}

class AsyncClientTest : public FeltdTest {
 protected:
  void connect(AsyncClient& client) { client.connect("127.0.0.1", server_->port(), "async"); }
};

TEST_F(AsyncClientTest, AProxyUpdateIsAnsweredWithItsStampAndTheForce) {
  Inbox<std::pair<v1::ForceUpdate, std::uint64_t>> forces;
  AsyncClient client;  // after what its handlers fill: its thread ends before they go
  client.on_force([&](const v1::ForceUpdate& force, std::uint64_t read_us) {
    forces.put({force, read_us});
  });
  connect(client);
  const std::uint64_t before = client::steady_microseconds();
  client.send_proxy_update(0, {0, 1.2, 0.01});  // 1 cm into the curtain at 400 N/m
  ASSERT_TRUE(forces.wait_for(1, scaled(5s)));
  const auto [force, read_us] = forces.items()[0];
  EXPECT_GE(force.client_time_us(), before);
  EXPECT_LE(force.client_time_us(), read_us);
  EXPECT_LT(read_us, client::steady_microseconds() + 1);
  EXPECT_TRUE(force.in_contact());
  EXPECT_NEAR(force.force().z(), 4, 1);
}

TEST_F(AsyncClientTest, HundredsOfUpdatesInFlightFromTwoThreadsAreEachAnsweredOnce) {
  Inbox<std::uint64_t> stamps;
  AsyncClient client;
  client.on_force(
      [&](const v1::ForceUpdate& force, std::uint64_t) { stamps.put(force.client_time_us()); });
  connect(client);
  constexpr std::uint64_t kPerThread = 300;
  const auto burst = [&](std::uint64_t first_stamp, double x) {
    for (std::uint64_t k = 0; k < kPerThread; ++k) {
      client.send(proxy_update(0, {x, 1.2, 0.01}, first_stamp + k));
    }
  };
  std::thread other(burst, 1'000'000, -0.2);
  burst(1, 0.2);
  other.join();
  ASSERT_TRUE(stamps.wait_for(2 * kPerThread, 10s)) << stamps.items().size() << " answered";
  const std::vector<std::uint64_t> answered = stamps.items();
  std::set<std::uint64_t> expected;
  for (std::uint64_t k = 0; k < kPerThread; ++k) {
    expected.insert(1 + k);
    expected.insert(1'000'000 + k);
  }
  EXPECT_EQ(std::set<std::uint64_t>(answered.begin(), answered.end()), expected);
  EXPECT_EQ(answered.size(), expected.size());  // none twice
}

TEST_F(AsyncClientTest, EachReplyGoesToItsOwnRequestsHandler) {
  Inbox<std::uint64_t> forces;
  Inbox<v1::Frame> frames;
  Inbox<std::pair<std::size_t, v1::ServerMessage>> replies;
  AsyncClient client;
  client.on_force([&](const v1::ForceUpdate& f, std::uint64_t) { forces.put(f.client_time_us()); });
  client.on_frame([&](const v1::Frame& frame) { frames.put(frame); });
  connect(client);
  // deferred requests (pause, step: the physics thread) among immediate ones, which overtake
  // them, with updates that have no handler in between
  std::vector<v1::ClientMessage> requests(5);
  requests[0].mutable_pause_scene();
  requests[1].mutable_step_scene()->set_steps(200);
  requests[2].mutable_list_scenes();
  requests[3].mutable_open_proxy();
  requests[4].mutable_subscribe_frames()->set_max_rate_hz(60);
  const v1::ServerMessage::BodyCase expected[] = {
      v1::ServerMessage::kSceneStatus, v1::ServerMessage::kSceneStatus,
      v1::ServerMessage::kSceneList, v1::ServerMessage::kProxyOpened,
      v1::ServerMessage::kSubscribed};
  std::vector<std::uint64_t> ids;
  for (std::size_t r = 0; r < requests.size(); ++r) {
    ids.push_back(client.send(requests[r], [&, r](const v1::ServerMessage& reply) {
      replies.put({r, reply});
    }));
    client.send(proxy_update(0, {0, 1.2, 0.5}, r + 1));
  }
  ASSERT_TRUE(replies.wait_for(requests.size(), 10s));
  ASSERT_TRUE(forces.wait_for(requests.size(), 5s));
  for (const auto& [r, reply] : replies.items()) {
    EXPECT_EQ(reply.body_case(), expected[r]) << r << ": " << reply.ShortDebugString();
    EXPECT_EQ(reply.request_id(), ids[r]);
  }
  EXPECT_EQ(forces.items(), (std::vector<std::uint64_t>{1, 2, 3, 4, 5}));
  ASSERT_TRUE(frames.wait_for(1, scaled(5s)));
  EXPECT_EQ(frames.items()[0].bodies(0).vertex_count(), 400u);
}

TEST_F(AsyncClientTest, ErrorsGoToTheirHandlerOrToOnError) {
  Inbox<v1::Error> errors;
  Inbox<v1::ServerMessage> replies;
  AsyncClient client;
  client.on_error([&](const v1::Error& error) { errors.put(error); });
  connect(client);
  // a refused request with a handler: the handler has the Error
  v1::ClientMessage close;
  close.mutable_close_proxy()->set_proxy_id(99);
  const std::uint64_t id = client.send(close, [&](const v1::ServerMessage& m) { replies.put(m); });
  ASSERT_TRUE(replies.wait_for(1, scaled(5s)));
  EXPECT_EQ(replies.items()[0].error().code(), v1::ERROR_CODE_UNKNOWN_ID);
  EXPECT_EQ(replies.items()[0].error().request_id(), id);
  // refused updates without one: on_error; a NaN position, then a 17th proxy
  client.send(proxy_update(0, {std::numeric_limits<double>::quiet_NaN(), 1, 0}, 1));
  for (std::uint32_t proxy = 1; proxy <= 17; ++proxy) {
    client.send(proxy_update(proxy, {0, 1.2, 0.5}, proxy));
  }
  ASSERT_TRUE(errors.wait_for(2, scaled(5s)));
  EXPECT_EQ(errors.items()[0].code(), v1::ERROR_CODE_BAD_REQUEST);
  EXPECT_EQ(errors.items()[0].message(), "position must be three numbers within ±1e6 m");
  EXPECT_EQ(errors.items()[1].code(), v1::ERROR_CODE_LIMIT_EXCEEDED);
  EXPECT_EQ(errors.items()[1].message(), "at most 16 proxies per client (--max-proxies)");
  // request() throws its Error
  try {
    client.request(close);
    ADD_FAILURE() << "no error";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_UNKNOWN_ID);
  }
  EXPECT_EQ(errors.items().size(), 2u);
  EXPECT_TRUE(client.connected());
}

/// Pauses the scene and sends a StepScene long enough to be still waiting when the server
/// goes; returns once the server has read it.
std::shared_ptr<Inbox<v1::ServerMessage>> send_long_step(AsyncClient& client) {
  v1::ClientMessage pause;
  pause.mutable_pause_scene();
  client.request(pause);
  auto reply = std::make_shared<Inbox<v1::ServerMessage>>();
  v1::ClientMessage step;
  step.mutable_step_scene()->set_steps(100'000);
  client.send(step, [reply](const v1::ServerMessage& m) { reply->put(m); });
  // answered at once, so after the step was read
  v1::ClientMessage list;
  list.mutable_list_scenes();
  client.request(list);
  return reply;
}

TEST_F(AsyncClientTest, AServerThatShutsDownTellsTheClientAndEndsWhatWaits) {
  Inbox<v1::SceneEvent> events;
  Inbox<v1::Error> errors;
  AsyncClient client;
  client.on_event([&](const v1::SceneEvent& event) { events.put(event); });
  client.on_error([&](const v1::Error& error) { errors.put(error); });
  connect(client);
  const auto step = send_long_step(client);
  ASSERT_EQ(server_->stop(SIGTERM, 5s), 0);
  ASSERT_TRUE(step->wait_for(1, scaled(5s)));
  EXPECT_EQ(step->items()[0].error().code(), v1::ERROR_CODE_CANCELLED);
  ASSERT_TRUE(events.wait_for(1, scaled(5s)));
  EXPECT_EQ(events.items().back().kind(), v1::EVENT_KIND_SERVER_SHUTDOWN);
  ASSERT_TRUE(errors.wait_for(1, scaled(5s)));
  EXPECT_EQ(errors.items()[0].message(), "the server closed the connection");
  EXPECT_FALSE(client.connected());
  // a request after the end fails at once instead of waiting for its timeout
  const auto start = Clock::now();
  v1::ClientMessage stats;
  stats.mutable_get_stats();
  EXPECT_THROW(client.request(stats), ClientError);
  EXPECT_LT(Clock::now() - start, 1s);
}

TEST_F(AsyncClientTest, ARequestWaitingWhenTheServerDiesGetsAnError) {
  AsyncClient client;
  connect(client);
  const auto step = send_long_step(client);
  server_->stop(SIGKILL, 5s);
  ASSERT_TRUE(step->wait_for(1, scaled(5s)));
  EXPECT_TRUE(step->items()[0].has_error());
  EXPECT_FALSE(client.connected());
}

TEST_F(AsyncClientTest, CloseEndsWhatWaitsWithoutCallingItAnError) {
  Inbox<v1::Error> errors;
  AsyncClient client;
  client.on_error([&](const v1::Error& error) { errors.put(error); });
  connect(client);
  const auto step = send_long_step(client);
  client.close();
  ASSERT_TRUE(step->wait_for(1, scaled(5s)));
  EXPECT_EQ(step->items()[0].error().message(), "the connection was closed");
  EXPECT_FALSE(client.connected());
  EXPECT_TRUE(errors.items().empty());
}

class OneClientOnly : public AsyncClientTest {
  std::vector<std::string> extra_args() const override { return {"--max-clients", "1"}; }
};

TEST_F(OneClientOnly, ConnectingToAFullServerSaysSoAtOnce) {
  AsyncClient first;
  connect(first);
  AsyncClient second;
  const auto start = Clock::now();
  try {
    connect(second);
    ADD_FAILURE() << "a second client was let in";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_LIMIT_EXCEEDED) << e.what();
    EXPECT_EQ(std::string(e.what()), "the server already serves 1 clients (--max-clients)");
  }
  EXPECT_LT(Clock::now() - start, 2s);  // not the Hello's 5 s timeout
  EXPECT_FALSE(second.connected());
}

}  // namespace
}  // namespace felt::test
