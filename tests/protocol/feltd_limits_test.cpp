// End to end: feltd's limits set small. A request past one gets LIMIT_EXCEEDED naming the flag
// (an inbound frame past its limit, FRAME_TOO_LARGE and the connection closed), nothing
// changes, and requests within the limits are served as asked.

#include "feltd_fixture.hpp"
#include "wire/message_codec.hpp"

namespace felt::test {
namespace {

class FeltdSmallLimitsTest : public FeltdTest {
 protected:
  std::vector<std::string> extra_args() const override {
    return {"--max-scenes",  "2", "--max-particles",   "1000", "--max-frame-rate", "100",
            "--max-proxies", "2", "--max-frame-bytes", "1024"};
  }
};

TEST_F(FeltdSmallLimitsTest, WelcomeReportsTheLimits) {
  Client client;
  connect(client);
  const v1::Limits limits = client.hello("curious").limits();
  EXPECT_EQ(limits.max_scenes(), 2u);
  EXPECT_EQ(limits.max_particles_per_scene(), 1000u);
  EXPECT_DOUBLE_EQ(limits.max_frame_rate_hz(), 100);
  EXPECT_EQ(limits.max_proxies(), 2u);
  EXPECT_EQ(limits.max_frame_bytes(), 1024u);
}

TEST_F(FeltdSmallLimitsTest, ScenesPastTheLimitAreRefusedUntilOneGoes) {
  auto first = greeted("first");
  first->create_scene({});  // with the server's own: two
  auto second = greeted("second");
  expect_error([&] { second->load_scene_by_name("default"); }, v1::ERROR_CODE_LIMIT_EXCEEDED,
               "the server already runs 2 scenes (--max-scenes)");
  expect_error([&] { second->create_scene({}); }, v1::ERROR_CODE_LIMIT_EXCEEDED, "--max-scenes");
  EXPECT_EQ(second->list_scenes().running_size(), 2);
  // the first client's scene goes with it
  first->leave_scene();
  EXPECT_EQ(second->list_scenes().running_size(), 1);
  EXPECT_NE(second->load_scene_by_name("default").scene_id(), 0u);
}

TEST_F(FeltdSmallLimitsTest, ParticlesPastTheLimitAreRefusedOnLoadAndOnAdd) {
  auto client = greeted("builder");
  expect_error(
      [&] {
        client->load_scene_json(R"({"bodies": [{"type": "cloth", "grid": {"nx": 40, "ny": 40}}]})");
      },
      v1::ERROR_CODE_LIMIT_EXCEEDED,
      "bodies[0].grid: 1600 particles exceed the 1000 the scene's particle limit leaves "
      "(--max-particles)");
  // the default scene's curtain has 400 of the 1000
  expect_error([&] { client->add_body(R"({"type": "cloth", "grid": {"nx": 30, "ny": 30}})"); },
               v1::ERROR_CODE_LIMIT_EXCEEDED,
               "body.grid: 900 particles exceed the 600 the scene's particle limit leaves "
               "(--max-particles)");
  EXPECT_EQ(client->stats().scene().bodies(), 1u);  // nothing was added
  EXPECT_EQ(client->list_scenes().running_size(), 1);
  EXPECT_EQ(client->add_body(small_cloth_json()).body().particles(), 36u);
  // a mistake in the document is still a bad scene
  expect_error([&] { client->add_body(R"({"type": "cloth", "grid": {"nx": 1}})"); },
               v1::ERROR_CODE_BAD_SCENE);
}

TEST_F(FeltdSmallLimitsTest, FramesComeAtTheRateAskedUpToTheLimit) {
  auto client = greeted("watcher");
  expect_error([&] { client->subscribe_frames(100.5); }, v1::ERROR_CODE_LIMIT_EXCEEDED,
               "max_rate_hz 100.5 is above the limit of 100 (--max-frame-rate)");
  EXPECT_DOUBLE_EQ(client->subscribe_frames(100).rate_hz(), 100);
  EXPECT_DOUBLE_EQ(client->subscribe_frames(12.5).rate_hz(), 12.5);
  EXPECT_DOUBLE_EQ(client->subscribe_frames(0).rate_hz(), 60);  // the default
  expect_error([&] { client->subscribe_frames(1000); }, v1::ERROR_CODE_LIMIT_EXCEEDED,
               "--max-frame-rate");
  // the refused request left the subscription as it was
  EXPECT_TRUE(client->next_frame(scaled(5s)));
}

TEST_F(FeltdSmallLimitsTest, ProxiesPastTheLimitAreRefusedOnOpenAndOnUpdate) {
  auto client = greeted("toucher");
  const std::uint32_t first = client->open_proxy().proxy_id();
  const std::uint32_t second = client->open_proxy().proxy_id();
  expect_error([&] { client->open_proxy(); }, v1::ERROR_CODE_LIMIT_EXCEEDED,
               "at most 2 proxies per client (--max-proxies)");
  // an update of a proxy not open would open a third
  expect_error(
      [&] {
        client->proxy_update(7, {5, 5, 5});
      },
      v1::ERROR_CODE_LIMIT_EXCEEDED, "--max-proxies");
  EXPECT_EQ(client->stats().session().open_proxies(), 2u);
  EXPECT_FALSE(client->proxy_update(second, {5, 5, 5}).in_contact());
  client->close_proxy(first);
  EXPECT_FALSE(client->proxy_update(7, {5, 5, 5}).in_contact());
}

/// A Hello whose ClientMessage takes exactly `bytes` bytes.
std::string hello_of_size(std::size_t bytes) {
  v1::ClientMessage message;
  message.set_request_id(1);
  message.mutable_hello()->set_protocol_version(1);
  message.mutable_hello()->set_client_name("");
  while (message.ByteSizeLong() < bytes)
    message.mutable_hello()->mutable_client_name()->push_back('a');
  EXPECT_EQ(message.ByteSizeLong(), bytes);
  std::string frame;
  wire::append_message(frame, message);
  return frame;
}

TEST_F(FeltdSmallLimitsTest, AnInboundFramePastTheLimitClosesOnlyItsConnection) {
  auto other = greeted("other");
  Client exact;
  connect(exact);
  exact.send_raw(hello_of_size(1024));
  const auto welcome = exact.receive(scaled(5s));
  ASSERT_TRUE(welcome);
  EXPECT_TRUE(welcome->has_welcome());
  Client over;
  connect(over);
  over.send_raw(hello_of_size(1025));
  const auto refused = over.receive(scaled(5s));
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->error().code(), v1::ERROR_CODE_FRAME_TOO_LARGE);
  EXPECT_EQ(refused->error().request_id(), 0u);
  EXPECT_EQ(refused->error().message(), "frame of 1025 bytes exceeds the limit of 1024");
  EXPECT_THROW(over.receive(scaled(5s)), ClientError);  // and closed
  EXPECT_FALSE(other->proxy_update(0, {5, 5, 5}).in_contact());
  EXPECT_FALSE(exact.proxy_update(0, {5, 5, 5}).in_contact());
}

}  // namespace
}  // namespace felt::test
