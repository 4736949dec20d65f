// ClientMessage dispatch through the real request handlers (server/net): each input is what a
// client writes after its Hello, sent on a loopback connection to a server in this process
// (tests/net/in_process_server.hpp) that serves scenes/default.json with scenes/ as its scene
// directory, started afresh for every input so that one input's scenes and settings do not
// leak into the next. Every request in the input that is a ClientMessage gets a reply or an
// Error with its id, unless the server closes the connection (after an Error with id 0, for
// bytes that are not a ClientMessage); when the input ends on a frame boundary a last GetStats
// must be answered too. The forces and frames that come back are finite.

#include <chrono>
#include <cmath>
#include <set>

#include "felt_client.hpp"
#include "fuzz_target.hpp"
#include "net/in_process_server.hpp"
#include "scene/scene_loader.hpp"
#include "wire/frame_codec.hpp"
#include "wire/message_codec.hpp"

namespace felt::fuzz {
namespace {

namespace v1 = felt::v1;
using namespace std::chrono_literals;

/// Longer than any single request of the input may take (a big scene loaded and stepped).
constexpr auto kReplyDeadline = 60s;
constexpr std::uint64_t kLastRequestId = ~std::uint64_t{0};

/// The ids of the requests the server will read in `input`: the frames up to the first that is
/// not a ClientMessage (the server closes the connection there). Sets `ends_cleanly` when the
/// input ends on a frame boundary.
std::multiset<std::uint64_t> request_ids(std::string_view input, std::size_t max_frame_bytes,
                                         bool& ends_cleanly) {
  std::multiset<std::uint64_t> ids;
  wire::FrameDecoder decoder(max_frame_bytes);
  decoder.feed(input);
  for (;;) {
    const wire::DecodeResult frame = decoder.next();
    v1::ClientMessage message;
    if (frame.status != wire::DecodeStatus::kFrame) {
      ends_cleanly = frame.status == wire::DecodeStatus::kNeedMore && decoder.buffered() == 0;
      return ids;
    }
    if (!wire::parse_message(frame.payload, message)) {
      ends_cleanly = false;
      return ids;
    }
    ids.insert(message.request_id());
  }
}

bool finite(const v1::Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

/// What the server publishes is finite.
void check_published(const v1::ServerMessage& message) {
  if (message.has_force_update()) {
    const v1::ForceUpdate& update = message.force_update();
    check(finite(update.force()) && finite(update.contact_point()) && finite(update.proxy()),
          "a force, its contact point and its proxy are finite");
  }
  if (message.has_frame()) {
    for (const v1::BodyFrame& body : message.frame().bodies()) {
      for (const float x : body.positions()) check(std::isfinite(x), "frame positions are finite");
    }
  }
}

}  // namespace
}  // namespace felt::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace felt;
  using namespace felt::fuzz;
  auto scene = load_scene_file(FELT_SCENE_DIR "/default.json");
  check(scene.has_value(), "scenes/default.json loads");
  net::InProcessServer server(std::move(*scene));
  std::string input(as_text(data, size));
  bool ends_cleanly = false;
  std::multiset<std::uint64_t> waiting =
      request_ids(input, server.context().options.max_inbound_frame_bytes, ends_cleanly);
  if (ends_cleanly) {
    v1::ClientMessage last;
    last.set_request_id(kLastRequestId);
    last.mutable_get_stats();
    wire::append_message(input, last);
    waiting.insert(kLastRequestId);
  }

  auto client = server.greeted("fuzz");
  client->send_raw(input);
  const auto deadline = std::chrono::steady_clock::now() + kReplyDeadline;
  while (!waiting.empty()) {
    std::optional<v1::ServerMessage> message;
    try {
      message = client->receive(std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now()));
    } catch (const client::ClientError&) {
      break;  // the server closed the connection
    }
    check(message.has_value(), "every request is answered in time");
    check_published(*message);
    const auto answered = waiting.find(message->request_id());
    if (answered != waiting.end() && !message->has_frame() && !message->has_event()) {
      waiting.erase(answered);
    }
  }
  return 0;
}
