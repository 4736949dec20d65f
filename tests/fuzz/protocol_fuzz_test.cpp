// The real feltd against random requests: every request type of felt.v1, its fields filled at
// random through protobuf's reflection (numbers extreme, NaN and infinite, unknown enum values,
// ids that name nothing, names that climb out of the scene directory, scene JSON whole or cut,
// long lists), sent over a few connections, over TCP and again over a WebSocket: bad input gets
// the same answer on both. Every request must get its reply or an Error with its id, unless the
// server closed the connection after an Error with id 0 (a string that is not UTF-8 does not
// parse); and at the end feltd still serves a new client of either transport as before.
//
// The seed and the number of cases are fixed so that CI sends the same requests every time;
// FELT_FUZZ_CASES and FELT_FUZZ_SEED send more, or others, by hand.

#include <signal.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <gtest/gtest.h>

#include "felt_client.hpp"
#include "fuzz_settings.hpp"
#include "protocol/feltd_process.hpp"
#include "support/time_scale.hpp"
#include "support/websocket_client.hpp"

namespace felt::test {
namespace {

namespace pb = google::protobuf;
namespace v1 = felt::v1;
using namespace std::chrono_literals;

class RandomRequests {
 public:
  explicit RandomRequests(std::uint64_t seed) : rng_(seed) {}

  /// A ClientMessage with one body, chosen at random, its fields filled at random.
  v1::ClientMessage next() {
    v1::ClientMessage message;
    const pb::OneofDescriptor* body = message.GetDescriptor()->FindOneofByName("body");
    const pb::FieldDescriptor* field = body->field(pick(body->field_count()));
    fill(*message.GetReflection()->MutableMessage(&message, field), 0);
    return message;
  }

 private:
  std::size_t pick(std::size_t n) { return static_cast<std::size_t>(rng_() % n); }
  bool one_in(std::size_t n) { return pick(n) == 0; }

  std::int64_t integer() {
    const std::int64_t values[] = {0,
                                   1,
                                   -1,
                                   2,
                                   3,
                                   16,
                                   100'000,
                                   std::numeric_limits<std::int32_t>::max(),
                                   std::numeric_limits<std::int64_t>::min(),
                                   std::int64_t{1} << 32,        // scene 0 at generation 1
                                   (std::int64_t{1} << 32) + 1,  // the next scene
                                   std::numeric_limits<std::int64_t>::max()};
    return one_in(2) ? static_cast<std::int64_t>(pick(400)) : values[pick(std::size(values))];
  }

  double real() {
    const double values[] = {0,
                             -0.0,
                             1,
                             -1,
                             1e-300,
                             1e300,
                             -1e300,
                             std::numeric_limits<double>::quiet_NaN(),
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()};
    if (one_in(2)) return std::uniform_real_distribution<double>(-3, 3)(rng_);
    return values[pick(std::size(values))];
  }

  std::string text() {
    static const std::string cloth =
        R"({"type": "cloth", "grid": {"nx": 6, "ny": 6, "center": [0, 1.5, 0.3]}, "pin": "top_corners"})";
    static const std::string scene = R"({"bodies": [)" + cloth + "]}";
    switch (pick(12)) {
      case 0:
        return "";
      case 1:
        return "default";
      case 2:
        return "thesis/three_cubes";
      case 3:
        return "../../../etc/passwd";
      case 4:
        return "/etc/passwd";
      case 5:
        return "meshes/bunny.obj";
      case 6:
        return std::string(100'000, 'x');
      case 7:
        return cloth;
      case 8:
        return scene;
      case 9:
        return scene.substr(0, pick(scene.size()));  // JSON cut short
      case 10:
        return R"({"type": "box", "half_extents": [0.1, 0.1, 0.1]})";
      default: {  // any bytes: a string field that is not UTF-8 does not parse
        std::string bytes(pick(32), '\0');
        for (char& c : bytes) c = static_cast<char>(rng_());
        return bytes;
      }
    }
  }

  void fill(pb::Message& message, int depth) {
    const pb::Descriptor* type = message.GetDescriptor();
    for (int i = 0; i < type->field_count(); ++i) {
      const pb::FieldDescriptor* field = type->field(i);
      if (one_in(3)) continue;  // left at its default
      // long lists in the request itself; nested in each other they would pass any frame limit
      const std::size_t count = !field->is_repeated()      ? 1
                                : depth <= 1 && one_in(20) ? 5000
                                                           : pick(5);
      for (std::size_t n = 0; n < count; ++n) put(message, field, depth);
    }
  }

  /// Sets field `f` of `m`, or adds an element to it when it is repeated, at random.
  void put(pb::Message& m, const pb::FieldDescriptor* f, int depth) {
    using F = pb::FieldDescriptor;
    const pb::Reflection& r = *m.GetReflection();
    const bool many = f->is_repeated();
    switch (f->cpp_type()) {
      case F::CPPTYPE_INT32: {
        const auto v = static_cast<std::int32_t>(integer());
        return many ? r.AddInt32(&m, f, v) : r.SetInt32(&m, f, v);
      }
      case F::CPPTYPE_INT64: {
        const std::int64_t v = integer();
        return many ? r.AddInt64(&m, f, v) : r.SetInt64(&m, f, v);
      }
      case F::CPPTYPE_UINT32: {
        const auto v = static_cast<std::uint32_t>(integer());
        return many ? r.AddUInt32(&m, f, v) : r.SetUInt32(&m, f, v);
      }
      case F::CPPTYPE_UINT64: {
        const auto v = static_cast<std::uint64_t>(integer());
        return many ? r.AddUInt64(&m, f, v) : r.SetUInt64(&m, f, v);
      }
      case F::CPPTYPE_DOUBLE: {
        const double v = real();
        return many ? r.AddDouble(&m, f, v) : r.SetDouble(&m, f, v);
      }
      case F::CPPTYPE_FLOAT: {
        const auto v = static_cast<float>(real());
        return many ? r.AddFloat(&m, f, v) : r.SetFloat(&m, f, v);
      }
      case F::CPPTYPE_BOOL: {
        const bool v = one_in(2);
        return many ? r.AddBool(&m, f, v) : r.SetBool(&m, f, v);
      }
      case F::CPPTYPE_ENUM: {  // unknown values too: proto3 keeps them
        const int v = static_cast<int>(pick(8)) - 1;
        return many ? r.AddEnumValue(&m, f, v) : r.SetEnumValue(&m, f, v);
      }
      case F::CPPTYPE_STRING: {
        std::string v = text();
        return many ? r.AddString(&m, f, std::move(v)) : r.SetString(&m, f, std::move(v));
      }
      case F::CPPTYPE_MESSAGE:
        if (depth < 4) fill(many ? *r.AddMessage(&m, f) : *r.MutableMessage(&m, f), depth + 1);
        return;
    }
  }
  std::mt19937_64 rng_;
};

/// The port of `server` that `Connection` speaks to.
template <class Connection>
std::uint16_t port_of(const FeltdProcess& server) {
  return std::is_same_v<Connection, WebSocketClient> ? server.web_port() : server.port();
}

/// A connection that has said Hello; a new one when the server closed the last.
template <class Connection>
std::unique_ptr<Connection> connected(const FeltdProcess& server, const std::string& name) {
  auto client = std::make_unique<Connection>();
  client->connect("127.0.0.1", port_of<Connection>(server));
  client->hello(name);
  return client;
}

/// What became of one request on its connection.
enum class Outcome { kSucceeded, kRefused, kConnectionClosed, kNoAnswer };

/// Waits for the reply to `request_id`, skipping frames and events.
template <class Connection>
Outcome await_reply(Connection& client, std::uint64_t request_id) {
  const auto deadline = std::chrono::steady_clock::now() + scaled(20s);
  while (std::chrono::steady_clock::now() < deadline) {
    std::optional<v1::ServerMessage> message;
    try {
      message = client.receive(200ms);
    } catch (const std::exception&) {
      return Outcome::kConnectionClosed;
    }
    if (!message) continue;
    if (message->request_id() == request_id) {
      if (!message->has_error()) return Outcome::kSucceeded;
      EXPECT_FALSE(message->error().message().empty());
      EXPECT_EQ(message->error().request_id(), request_id);
      return Outcome::kRefused;
    }
    // a fatal Error with id 0 is about the connection: it closes next
    if (message->request_id() == 0 && message->has_error()) return Outcome::kConnectionClosed;
  }
  return Outcome::kNoAnswer;
}

/// Sends the random requests over connections of type `Connection` (TCP or WebSocket).
template <class Connection>
void fuzz(FeltdProcess& server) {
  const FuzzSettings settings = fuzz_settings(300);
  RandomRequests requests(settings.seed);
  const std::uint64_t cases = settings.cases;
  constexpr int kConnections = 3;
  std::vector<std::unique_ptr<Connection>> clients;
  const auto name = [](int c) { return "fuzz-" + std::to_string(c); };
  for (int c = 0; c < kConnections; ++c) clients.push_back(connected<Connection>(server, name(c)));
  // the largest request feltd takes (--max-frame-bytes), as its Welcome says
  const std::uint64_t max_frame_bytes =
      connected<Connection>(server, "fuzz-limits")->hello("fuzz-limits").limits().max_frame_bytes();

  int succeeded = 0, refused = 0, closed = 0;
  for (std::uint64_t n = 0; n < cases && !::testing::Test::HasFailure(); ++n) {
    const int c = static_cast<int>(n % kConnections);
    v1::ClientMessage message = requests.next();
    SCOPED_TRACE("case " + std::to_string(n) + ": " + message.ShortDebugString().substr(0, 2000));
    // past it: refused with FRAME_TOO_LARGE, and the connection closes, maybe while the client
    // is still sending it
    const bool oversized = message.ByteSizeLong() > max_frame_bytes;
    std::uint64_t id = 0;
    try {
      id = clients[c]->send(message);
    } catch (const std::exception&) {
      ASSERT_TRUE(server.running());
      clients[c] = connected<Connection>(server, name(c));  // closed after an earlier reply
      try {
        id = clients[c]->send(message);
      } catch (const std::exception& e) {
        ASSERT_TRUE(oversized) << "a new connection failed: " << e.what();
      }
    }
    const Outcome outcome = id == 0 ? Outcome::kConnectionClosed : await_reply(*clients[c], id);
    if (oversized) {
      EXPECT_EQ(outcome, Outcome::kConnectionClosed);
    }
    ASSERT_NE(outcome, Outcome::kNoAnswer);
    ASSERT_TRUE(server.running());
    if (outcome == Outcome::kSucceeded) ++succeeded;
    if (outcome == Outcome::kRefused) ++refused;
    if (outcome == Outcome::kConnectionClosed) {
      ++closed;
      clients[c] = connected<Connection>(server, name(c));
    }
  }
  std::cout << succeeded << " requests succeeded, " << refused << " were refused, " << closed
            << " closed their connection\n";
  // enough requests were well-formed to reach the handlers, and some got past their checks
  EXPECT_GT(succeeded + refused, static_cast<int>(cases) / 2);
  EXPECT_GT(succeeded, static_cast<int>(cases) / 20);

  // a new client of either transport is served as before (the requests may have changed the
  // shared default scene in any way, so not what it feels)
  client::Client after;
  after.connect("127.0.0.1", server.port());
  after.hello("after-the-fuzz");
  EXPECT_TRUE(after.stats().has_server());
  const v1::ForceUpdate touch = after.proxy_update(0, {0, 1.2, 0.01});
  EXPECT_TRUE(std::isfinite(touch.force().z()));
  WebSocketClient browser;
  browser.connect("127.0.0.1", server.web_port());
  browser.hello("after-the-fuzz-over-a-websocket");
  EXPECT_TRUE(browser.stats().has_server());
  EXPECT_TRUE(std::isfinite(browser.proxy_update(0, {0, 1.2, 0.01}).force().z()));
  EXPECT_EQ(server.stop(SIGTERM, 10s), 0);
}

std::vector<std::string> fuzzed_server() {
  return {"--scene-dir",  FELT_SCENE_DIR,
          "--scene",      std::string(FELT_SCENE_DIR) + "/default.json",
          "--max-scenes", "6",
          "--web",        "127.0.0.1:0"};
}

TEST(ProtocolFuzz, EveryRandomRequestOverTcpIsAnsweredAndTheServerServesOnAfterward) {
  FeltdProcess server(fuzzed_server());
  fuzz<client::Client>(server);
}

TEST(ProtocolFuzz, EveryRandomRequestOverAWebSocketIsAnsweredAndTheServerServesOnAfterward) {
  FeltdProcess server(fuzzed_server());
  fuzz<WebSocketClient>(server);
}

}  // namespace
}  // namespace felt::test
