// End to end: many clients at once, and clients that misbehave — vanish, send garbage, unknown
// ids or non-finite numbers, never say hello — while the others are served as before (the slow
// and flooding ones: feltd_slow_clients_test.cpp).

#include <cmath>
#include <set>

#include <google/protobuf/descriptor.h>

#include "feltd_fixture.hpp"
#include "wire/frame_codec.hpp"
#include "wire/message_codec.hpp"

namespace felt::test {
namespace {

TEST_F(FeltdTest, EveryRequestTypeGetsItsOwnReplyOrAnError) {
  auto client = greeted("curious");
  // each request with every field unset, in an order that leaves each one something to do:
  // its reply's field, or "error" and the code
  struct Expected {
    const char* request;
    const char* reply;
    v1::ErrorCode code = v1::ERROR_CODE_UNSPECIFIED;
  };
  const Expected expected[] = {
      {"hello", "error", v1::ERROR_CODE_UNSUPPORTED_VERSION},  // version 0
      {"list_scenes", "scene_list"},
      {"get_stats", "stats"},
      {"load_scene", "error", v1::ERROR_CODE_BAD_REQUEST},  // no source
      {"subscribe_frames", "subscribed"},
      {"ack_frame", "error", v1::ERROR_CODE_BAD_REQUEST},     // frame 0
      {"proxy_update", "error", v1::ERROR_CODE_BAD_REQUEST},  // no position
      {"open_proxy", "proxy_opened"},
      {"close_proxy", "error", v1::ERROR_CODE_UNKNOWN_ID},  // proxy 0 was not opened
      {"set_body_parameters", "body_updated"},              // body 0, nothing to change
      {"pin_particles", "body_updated"},
      {"apply_force", "error", v1::ERROR_CODE_BAD_REQUEST},  // no vertices
      {"add_body", "error", v1::ERROR_CODE_BAD_REQUEST},     // no source
      {"remove_body", "body_removed"},                       // the curtain
      {"pause_scene", "scene_status"},
      {"resume_scene", "scene_status"},
      {"step_scene", "error", v1::ERROR_CODE_BAD_REQUEST},      // 0 steps
      {"set_time_scale", "error", v1::ERROR_CODE_BAD_REQUEST},  // scale 0
      {"save_state", "state_saved"},
      {"restore_state", "error", v1::ERROR_CODE_BAD_REQUEST},  // no source
      {"reset_scene", "scene_status"},                         // the curtain is back
      {"unsubscribe_frames", "unsubscribed"},
      {"join_scene", "error", v1::ERROR_CODE_UNKNOWN_ID},            // scene 0
      {"destroy_scene", "error", v1::ERROR_CODE_PERMISSION_DENIED},  // the server's own
      {"create_scene", "scene_loaded"},                              // joined
      {"destroy_scene", "scene_destroyed"},                          // the created one
      {"leave_scene", "error", v1::ERROR_CODE_NO_SCENE},
      {"join_scene", "error", v1::ERROR_CODE_UNKNOWN_ID},
  };
  const auto* body = v1::ClientMessage::descriptor()->FindOneofByName("body");
  ASSERT_NE(body, nullptr);
  std::set<std::string> untried;
  for (int f = 0; f < body->field_count(); ++f) untried.insert(body->field(f)->name());
  const google::protobuf::Reflection* reflection = v1::ClientMessage::GetReflection();
  for (const Expected& e : expected) {
    const auto* field = v1::ClientMessage::descriptor()->FindFieldByName(e.request);
    ASSERT_NE(field, nullptr) << e.request;
    untried.erase(e.request);
    v1::ClientMessage message;
    reflection->MutableMessage(&message, field);  // the request with every field unset
    const std::uint64_t id = client->send(message);
    std::optional<v1::ServerMessage> reply;
    while ((reply = client->receive(scaled(5s))) && reply->request_id() != id) {
    }
    ASSERT_TRUE(reply) << e.request;
    const auto* replied = v1::ServerMessage::descriptor()->FindFieldByNumber(reply->body_case());
    ASSERT_NE(replied, nullptr) << e.request;
    EXPECT_EQ(replied->name(), e.reply) << e.request << ": " << reply->ShortDebugString();
    if (reply->has_error()) {
      EXPECT_EQ(reply->error().code(), e.code) << e.request << ": " << reply->error().message();
      EXPECT_EQ(reply->error().request_id(), id);
    }
  }
  EXPECT_TRUE(untried.empty()) << "no expectation for " << *untried.begin();
  // a body this server does not know: an unknown field number of the oneof
  std::string unknown;
  wire::append_varint(unknown, (999u << 3) | 2);  // field 999, length-delimited
  wire::append_varint(unknown, 0);
  std::string frame;
  wire::append_frame(frame, unknown);
  client->send_raw(frame);
  const auto reply = client->receive(scaled(5s));
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->error().code(), v1::ERROR_CODE_UNKNOWN_MESSAGE);
}

TEST_F(FeltdTest, EightClientsTouchAndWatchOneSceneEachWithItsOwnProxy) {
  std::vector<std::unique_ptr<Client>> clients;
  for (int c = 0; c < 8; ++c) {
    clients.push_back(greeted("c" + std::to_string(c)));
    clients.back()->subscribe_frames(30);
  }
  EXPECT_EQ(clients[0]->stats().scene().clients(), 8u);
  for (int round = 0; round < 20; ++round) {
    for (int c = 0; c < 8; ++c) {
      // each presses its own spot of the curtain, 1 cm in front
      const double x = -0.35 + 0.1 * c;
      const v1::ForceUpdate force = clients[c]->proxy_update(0, {x, 1.2, 0.01});
      if (round == 0) {
        EXPECT_TRUE(force.in_contact()) << c;
        EXPECT_GT(force.force().z(), 1) << c;
      }
    }
  }
  for (auto& client : clients) {
    const auto frame = client->next_frame(scaled(5s));
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->bodies(0).positions_size(), 3 * 400);
  }
  // every client's 20 updates were solved
  EXPECT_GE(clients[0]->stats().scene().haptic_updates(), 160u);
}

TEST_F(FeltdTest, AClientThatVanishesMidStreamHurtsNoOne) {
  auto steady = greeted("steady");
  steady->subscribe_frames(60);
  {
    Client vanishing;
    connect(vanishing);
    vanishing.hello("vanishing");
    vanishing.subscribe_frames(240);
    vanishing.proxy_update(0, {0, 1.2, 0.01});
    // half a request, then gone without a goodbye
    std::string frame;
    v1::ClientMessage message;
    message.mutable_proxy_update()->mutable_position()->set_x(1);
    wire::append_message(frame, message);
    vanishing.send_raw(frame.substr(0, frame.size() / 2));
  }
  const auto left = steady->wait_event(v1::EVENT_KIND_CLIENT_LEFT, 5s);
  ASSERT_TRUE(left);
  EXPECT_EQ(left->client_name(), "vanishing");
  EXPECT_TRUE(steady->next_frame(scaled(5s)));
  EXPECT_FALSE(steady->proxy_update(0, {5, 5, 5}).in_contact());
  // the server's count follows the scene's news of the leaving when the connection has closed
  EXPECT_TRUE(eventually([&] { return steady->stats().server().clients() == 1; }));
}

TEST_F(FeltdTest, UnknownIdsAndNonFiniteNumbersGetErrorsAndNothingChanges) {
  auto client = greeted("sloppy");
  expect_error([&] { client->join_scene(12345); }, v1::ERROR_CODE_UNKNOWN_ID);
  expect_error([&] { client->remove_body(77); }, v1::ERROR_CODE_UNKNOWN_ID);
  expect_error([&] { client->pin_particles(77, {1}, {}); }, v1::ERROR_CODE_UNKNOWN_ID);
  expect_error([&] { client->close_proxy(3); }, v1::ERROR_CODE_UNKNOWN_ID);
  expect_error([&] { client->destroy_scene(99); }, v1::ERROR_CODE_UNKNOWN_ID);
  expect_error([&] { client->restore_state(5); }, v1::ERROR_CODE_UNKNOWN_ID);
  expect_error([&] { client->proxy_update(0, {0, NAN, 0}); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->proxy_update(0, {0, 0, -INFINITY}); }, v1::ERROR_CODE_BAD_REQUEST);
  v1::SetBodyParameters set;
  set.set_body_id(0);
  set.set_structural_stiffness(NAN);
  expect_error([&] { client->set_body_parameters(set); }, v1::ERROR_CODE_BAD_REQUEST);
  set.set_structural_stiffness(1e300);
  expect_error([&] { client->set_body_parameters(set); }, v1::ERROR_CODE_BAD_REQUEST);
  set.clear_structural_stiffness();
  set.set_integrator("warp_drive");
  expect_error([&] { client->set_body_parameters(set); }, v1::ERROR_CODE_BAD_REQUEST);
  v1::CreateScene create;
  create.mutable_gravity()->set_y(NAN);
  expect_error([&] { client->create_scene(create); }, v1::ERROR_CODE_BAD_SCENE);
  // the scene runs on, finite
  client->subscribe_frames(0);
  const auto frame = client->next_frame(scaled(5s));
  ASSERT_TRUE(frame);
  for (float x : frame->bodies(0).positions()) ASSERT_TRUE(std::isfinite(x));
}

TEST_F(FeltdTest, ATruncatedFrameThenSilenceLeavesTheServerServing) {
  Client truncated;
  connect(truncated);
  std::string prefix;
  wire::append_varint(prefix, 100);
  truncated.send_raw(prefix + "only ten b");  // 10 of the 100 bytes, then nothing
  auto other = greeted("other");
  EXPECT_FALSE(other->proxy_update(0, {5, 5, 5}).in_contact());
  EXPECT_FALSE(truncated.receive(300ms));  // the server waits for the rest, quietly
  truncated.close();
  EXPECT_FALSE(other->proxy_update(0, {5, 5, 5}).in_contact());
}

class ShortHelloDeadline : public FeltdTest {
  std::vector<std::string> extra_args() const override {
    return {"--hello-timeout-ms", "500", "--max-clients", "3"};
  }
};

TEST_F(ShortHelloDeadline, ConnectionsThatNeverSayHelloAreClosedAndFreeTheirSlots) {
  auto patient = greeted("patient");
  const auto before = std::chrono::steady_clock::now();
  Client silent;
  connect(silent);
  Client half;  // half a Hello, then nothing
  connect(half);
  v1::ClientMessage hello;
  hello.mutable_hello()->set_protocol_version(1);
  std::string frame;
  wire::append_message(frame, hello);
  half.send_raw(frame.substr(0, frame.size() - 1));
  // meanwhile they hold every slot, and the greeted client is served
  Client refused;
  connect(refused);
  const auto full = refused.receive(scaled(5s));
  ASSERT_TRUE(full);
  EXPECT_EQ(full->error().code(), v1::ERROR_CODE_LIMIT_EXCEEDED);
  EXPECT_FALSE(patient->proxy_update(0, {5, 5, 5}).in_contact());
  for (Client* unknown : {&silent, &half}) {
    const auto error = unknown->receive(scaled(5s));
    ASSERT_TRUE(error);
    EXPECT_EQ(error->error().code(), v1::ERROR_CODE_HELLO_REQUIRED) << error->error().message();
    EXPECT_EQ(error->error().request_id(), 0u);
    EXPECT_THROW(unknown->receive(scaled(5s)), ClientError);  // and closed
  }
  EXPECT_GE(std::chrono::steady_clock::now() - before, 500ms);
  // the greeted client, past its own deadline, is still served, and the slots are free again
  EXPECT_FALSE(patient->proxy_update(0, {5, 5, 5}).in_contact());
  EXPECT_TRUE(eventually([&] { return patient->stats().server().clients() == 1; }));
  auto second = greeted("second");
  auto third = greeted("third");
  EXPECT_EQ(third->stats().server().clients(), 3u);
}

TEST_F(FeltdTest, ShutdownTellsEveryClientFirst) {
  auto a = greeted("a");
  auto b = greeted("b");
  a->subscribe_frames(60);
  ASSERT_EQ(server_->stop(SIGTERM, 5s), 0);
  for (Client* client : {a.get(), b.get()}) {
    EXPECT_TRUE(client->wait_event(v1::EVENT_KIND_SERVER_SHUTDOWN, 5s));
  }
}

// docs/protocol.md, section 1: at SIGTERM a request still waiting in a scene is answered
// CANCELLED, then every session hears SERVER_SHUTDOWN (naming its scene, or 0) and is closed.
TEST_F(FeltdTest, ShutdownCancelsWhatScenesStillHadToDoThenSaysGoodbye) {
  auto busy = greeted("busy");
  // 100,000 steps of a 100 x 100 cloth take a minute
  const std::uint64_t scene =
      busy->load_scene_json(R"({"bodies": [{"type": "cloth", "grid": {"nx": 100, "ny": 100}}]})")
          .scene_id();
  busy->pause();
  const std::vector<std::uint64_t> ids = send_steps(*busy, 2, 100'000);
  ASSERT_EQ(busy->stats().session().requests_in_flight(), 2u);
  auto idle = greeted("idle");
  idle->leave_scene();
  ASSERT_EQ(server_->stop(SIGTERM, 5s), 0);
  std::vector<v1::ServerMessage> received;
  try {
    while (auto message = busy->receive(scaled(5s))) received.push_back(*message);
    ADD_FAILURE() << "the connection was not closed";
  } catch (const ClientError&) {
  }
  std::erase_if(received, tells_of_a_rescue);  // the big cloth may need substeps now and then
  ASSERT_EQ(received.size(), 3u) << describe(received);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(received[i].request_id(), ids[i]);
    EXPECT_EQ(received[i].error().code(), v1::ERROR_CODE_CANCELLED);
    EXPECT_EQ(received[i].error().request_id(), ids[i]);
    EXPECT_EQ(received[i].error().message(), "the scene was stopped");
  }
  const v1::SceneEvent& goodbye = received[2].event();
  EXPECT_EQ(goodbye.kind(), v1::EVENT_KIND_SERVER_SHUTDOWN);
  EXPECT_EQ(goodbye.scene_id(), scene);
  EXPECT_EQ(goodbye.sequence(), 0u);
  EXPECT_EQ(received[2].request_id(), 0u);
  const auto idle_goodbye = idle->wait_event(v1::EVENT_KIND_SERVER_SHUTDOWN, 5s);
  ASSERT_TRUE(idle_goodbye);
  EXPECT_EQ(idle_goodbye->scene_id(), 0u);
}

}  // namespace
}  // namespace felt::test
