// The synchronous client's typed requests against a fake server: a reply of another kind, an
// Error for another request and the server's last Error (request id 0) are each taken for what
// they are, never as an empty reply.

#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "fake_server.hpp"
#include "felt_client.hpp"

namespace felt::test {
namespace {

namespace v1 = felt::v1;
using client::Client;
using client::ClientError;

/// A reply to `request` that sets `kind` (a field of ServerMessage's oneof) to its default.
v1::ServerMessage reply_of_kind(const v1::ClientMessage& request, const std::string& kind) {
  v1::ServerMessage reply;
  reply.set_request_id(request.request_id());
  const auto* field = v1::ServerMessage::descriptor()->FindFieldByName(kind);
  reply.GetReflection()->MutableMessage(&reply, field);
  return reply;
}

v1::ServerMessage error_reply(std::uint64_t request_id, v1::ErrorCode code,
                              const std::string& text) {
  v1::ServerMessage reply;
  reply.set_request_id(request_id);
  reply.mutable_error()->set_code(code);
  reply.mutable_error()->set_message(text);
  reply.mutable_error()->set_request_id(request_id);
  return reply;
}

struct TypedCall {
  const char* name;
  std::function<void(Client&)> call;
  const char* reply;  ///< the ServerMessage field it expects
};

const TypedCall kTypedCalls[] = {
    {"hello", [](Client& c) { c.hello("t"); }, "welcome"},
    {"stats", [](Client& c) { c.stats(); }, "stats"},
    {"list_scenes", [](Client& c) { c.list_scenes(); }, "scene_list"},
    {"load_scene_by_name", [](Client& c) { c.load_scene_by_name("default"); }, "scene_loaded"},
    {"load_scene_json", [](Client& c) { c.load_scene_json("{}"); }, "scene_loaded"},
    {"create_scene", [](Client& c) { c.create_scene({}); }, "scene_loaded"},
    {"join_scene", [](Client& c) { c.join_scene(1); }, "scene_loaded"},
    {"leave_scene", [](Client& c) { c.leave_scene(); }, "scene_left"},
    {"destroy_scene", [](Client& c) { c.destroy_scene(1); }, "scene_destroyed"},
    {"pause", [](Client& c) { c.pause(); }, "scene_status"},
    {"resume", [](Client& c) { c.resume(); }, "scene_status"},
    {"step", [](Client& c) { c.step(1); }, "scene_status"},
    {"set_time_scale", [](Client& c) { c.set_time_scale(1); }, "scene_status"},
    {"reset", [](Client& c) { c.reset(); }, "scene_status"},
    {"save_state", [](Client& c) { c.save_state(); }, "state_saved"},
    {"restore_state(id)", [](Client& c) { c.restore_state(1); }, "scene_status"},
    {"restore_state(data)", [](Client& c) { c.restore_state(v1::SceneState{}); }, "scene_status"},
    {"add_body", [](Client& c) { c.add_body("{}"); }, "body_added"},
    {"add_collider", [](Client& c) { c.add_collider("{}"); }, "body_added"},
    {"remove_body", [](Client& c) { c.remove_body(0); }, "body_removed"},
    {"set_body_parameters", [](Client& c) { c.set_body_parameters({}); }, "body_updated"},
    {"pin_particles", [](Client& c) { c.pin_particles(0, {1}, {}); }, "body_updated"},
    {"apply_force",
     [](Client& c) {
       c.apply_force(0, {1}, {0, 0, 1}, 0.1);
     },
     "body_updated"},
    {"open_proxy", [](Client& c) { c.open_proxy(); }, "proxy_opened"},
    {"close_proxy", [](Client& c) { c.close_proxy(1); }, "proxy_closed"},
    {"proxy_update",
     [](Client& c) {
       c.proxy_update(0, {0, 0, 0});
     },
     "force_update"},
    {"subscribe_frames", [](Client& c) { c.subscribe_frames(30); }, "subscribed"},
    {"unsubscribe_frames", [](Client& c) { c.unsubscribe_frames(); }, "unsubscribed"},
    {"ack_frame", [](Client& c) { c.ack_frame(1); }, "frame_acked"},
};

TEST(ClientRequests, EveryTypedCallRefusesAReplyOfAnotherKind) {
  for (const TypedCall& typed : kTypedCalls) {
    SCOPED_TRACE(typed.name);
    // any kind but the expected one: a frame_acked, or a welcome where frame_acked is expected
    const std::string wrong = std::string(typed.reply) == "frame_acked" ? "welcome" : "frame_acked";
    FakeServer server([&](const v1::ClientMessage& request) {
      return FakeAnswer{{reply_of_kind(request, wrong)}};
    });
    Client client;
    client.connect("127.0.0.1", server.port());
    try {
      typed.call(client);
      ADD_FAILURE() << "a " << wrong << " was taken for a " << typed.reply;
    } catch (const ClientError& e) {
      EXPECT_EQ(std::string(e.what()),
                "the server answered with " + wrong + " instead of " + typed.reply);
    }
  }
}

TEST(ClientRequests, EveryTypedCallTakesItsOwnKindOfReply) {
  for (const TypedCall& typed : kTypedCalls) {
    SCOPED_TRACE(typed.name);
    FakeServer server([&](const v1::ClientMessage& request) {
      return FakeAnswer{{reply_of_kind(request, typed.reply)}};
    });
    Client client;
    client.connect("127.0.0.1", server.port());
    EXPECT_NO_THROW(typed.call(client));
  }
}

TEST(ClientRequests, RepliesAndErrorsForOtherRequestsAreSkipped) {
  // a late reply and a late Error to earlier requests (that timed out) come first
  FakeServer server([](const v1::ClientMessage& request) {
    v1::ServerMessage late = reply_of_kind(request, "stats");
    late.set_request_id(request.request_id() + 100);
    late.mutable_stats()->mutable_server()->set_clients(1);
    v1::ServerMessage mine = reply_of_kind(request, "stats");
    mine.mutable_stats()->mutable_server()->set_clients(7);
    return FakeAnswer{
        {late, error_reply(request.request_id() + 101, v1::ERROR_CODE_NO_SCENE, "late"), mine}};
  });
  Client client;
  client.connect("127.0.0.1", server.port());
  EXPECT_EQ(client.stats().server().clients(), 7u);
}

TEST(ClientRequests, AnErrorForThisRequestThrowsItsCodeAndMessage) {
  FakeServer server([](const v1::ClientMessage& request) {
    return FakeAnswer{
        {error_reply(request.request_id(), v1::ERROR_CODE_NO_SCENE, "load or join a scene")}};
  });
  Client client;
  client.connect("127.0.0.1", server.port());
  try {
    client.stats();
    ADD_FAILURE() << "no error";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_NO_SCENE);
    EXPECT_STREQ(e.what(), "load or join a scene");
  }
}

TEST(ClientRequests, TheServersLastErrorEndsTheWaitWithItsReason) {
  // as feltd refuses a client over --max-clients: request id 0, then it hangs up
  FakeServer server([](const v1::ClientMessage&) {
    return FakeAnswer{{error_reply(0, v1::ERROR_CODE_LIMIT_EXCEEDED, "the server is full")}, true};
  });
  Client client;
  client.connect("127.0.0.1", server.port());
  try {
    client.hello("t");
    ADD_FAILURE() << "no error";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_LIMIT_EXCEEDED);
    EXPECT_STREQ(e.what(), "the server is full");
  }
}

}  // namespace
}  // namespace felt::test
