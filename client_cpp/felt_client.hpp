#pragma once
// felt_client: a synchronous client for scripts, tools and tests. Each call sends a request and
// waits for its reply; frames that arrive meanwhile are kept for next_frame().

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/asio.hpp>

#include "felt/v1/envelope.pb.h"
#include "wire/frame_codec.hpp"

namespace felt::client {

/// An Error reply from the server, or a connection that failed.
class ClientError : public std::runtime_error {
 public:
  ClientError(felt::v1::ErrorCode code, const std::string& message)
      : std::runtime_error(message), code_(code) {}
  explicit ClientError(const felt::v1::Error& error) : ClientError(error.code(), error.message()) {}
  felt::v1::ErrorCode code() const { return code_; }

 private:
  felt::v1::ErrorCode code_;
};

using Point = std::array<double, 3>;

/// What SubscribeFrames asks for.
struct FrameSubscription {
  double max_rate_hz = 0;  ///< 0: the server's default
  bool normals = false;
  std::vector<std::uint32_t> body_ids;  ///< empty: every body
  bool quantized = false;               ///< 16-bit positions (and normals)
  bool deltas = false;                  ///< quantized only: changes against acknowledged frames
  bool scalars = false;                 ///< a number per vertex: a cloth's strain
  /// frames not yet acknowledged (ack_frame) that the server may have sent, at most (0: any)
  std::uint32_t max_unacknowledged = 0;
};

class Client {
 public:
  Client();
  ~Client();

  /// Connects to HOST:PORT; throws ClientError on failure.
  void connect(const std::string& host, std::uint16_t port,
               std::chrono::milliseconds timeout = std::chrono::seconds(5));
  void close();

  felt::v1::Welcome hello(const std::string& client_name, const std::string& token = "");
  felt::v1::Stats stats();

  // scenes
  felt::v1::SceneList list_scenes();
  felt::v1::SceneLoaded load_scene_by_name(const std::string& name, bool shared = false);
  felt::v1::SceneLoaded load_scene_json(const std::string& json, bool shared = false);
  felt::v1::SceneLoaded create_scene(const felt::v1::CreateScene& create);
  felt::v1::SceneLoaded join_scene(std::uint64_t scene_id);
  felt::v1::SceneLeft leave_scene();
  felt::v1::SceneDestroyed destroy_scene(std::uint64_t scene_id = 0);
  felt::v1::SceneStatus pause();
  felt::v1::SceneStatus resume();
  felt::v1::SceneStatus step(std::uint32_t steps);
  felt::v1::SceneStatus set_time_scale(double scale);
  felt::v1::SceneStatus reset();
  felt::v1::StateSaved save_state(bool include_data = false);
  felt::v1::SceneStatus restore_state(std::uint32_t state_id);
  felt::v1::SceneStatus restore_state(const felt::v1::SceneState& state);

  // bodies
  felt::v1::BodyAdded add_body(const std::string& body_json);
  felt::v1::BodyAdded add_collider(const std::string& collider_json);
  felt::v1::BodyRemoved remove_body(std::uint32_t body_id);
  felt::v1::BodyUpdated set_body_parameters(const felt::v1::SetBodyParameters& parameters);
  felt::v1::BodyUpdated pin_particles(std::uint32_t body_id, const std::vector<std::uint32_t>& pin,
                                      const std::vector<std::uint32_t>& unpin);
  felt::v1::BodyUpdated apply_force(std::uint32_t body_id,
                                    const std::vector<std::uint32_t>& vertices, const Point& force,
                                    double duration);

  // haptics
  felt::v1::ProxyOpened open_proxy(const felt::v1::ProxySettings& settings = {});
  felt::v1::ProxyClosed close_proxy(std::uint32_t proxy_id);
  felt::v1::ForceUpdate proxy_update(std::uint32_t proxy_id, const Point& position,
                                     std::uint32_t buttons = 0);

  // frames
  felt::v1::Subscribed subscribe_frames(double max_rate_hz = 0, bool normals = false);
  felt::v1::Subscribed subscribe_frames(const FrameSubscription& subscription);
  felt::v1::Unsubscribed unsubscribe_frames();
  felt::v1::FrameAcked ack_frame(std::uint64_t sequence);
  /// Acknowledges a frame without waiting for the reply (which is skipped when it comes).
  void ack_frame_async(std::uint64_t sequence);

  /// The next frame, or nothing if none came within `timeout`.
  std::optional<felt::v1::Frame> next_frame(std::chrono::milliseconds timeout);
  /// The scene events received so far (with replies and frames), oldest first; forgets them.
  std::vector<felt::v1::SceneEvent> take_events();
  /// Waits up to `timeout` for an event of `kind` (keeping the others for take_events()).
  std::optional<felt::v1::SceneEvent> wait_event(felt::v1::EventKind kind,
                                                 std::chrono::milliseconds timeout);

  /// Sends `message` with a fresh request id and returns the reply with that id. An Error
  /// reply, or the server's Error before it closes the connection (request id 0), throws
  /// ClientError.
  felt::v1::ServerMessage request(felt::v1::ClientMessage& message);
  /// The same, and throws ClientError unless the reply is of the kind `expected`.
  felt::v1::ServerMessage request(felt::v1::ClientMessage& message,
                                  felt::v1::ServerMessage::BodyCase expected);
  /// Sends `message` with a fresh request id and returns the id, without waiting.
  std::uint64_t send(felt::v1::ClientMessage& message);

  /// Sends raw bytes (protocol tests use this to send garbage).
  void send_raw(const std::string& bytes);
  /// The next message of any kind, or nothing on timeout; throws when the connection ends.
  std::optional<felt::v1::ServerMessage> receive(std::chrono::milliseconds timeout);

  void set_reply_timeout(std::chrono::milliseconds timeout) { reply_timeout_ = timeout; }

 private:
  /// Keeps a frame or an event that arrived unasked; false for anything else.
  bool keep_streamed(felt::v1::ServerMessage& message);
  /// Waits until `deadline` for one more message and keeps it if it is streamed (anything
  /// else, a late reply, is dropped); false when none came.
  bool receive_streamed(std::chrono::steady_clock::time_point deadline);

  boost::asio::io_context io_;
  boost::asio::ip::tcp::socket socket_;
  wire::FrameDecoder decoder_;
  std::array<std::uint8_t, 64 * 1024> buffer_;
  std::deque<felt::v1::Frame> frames_;
  std::vector<felt::v1::SceneEvent> events_;
  std::uint64_t next_request_id_ = 1;
  std::chrono::milliseconds reply_timeout_ = std::chrono::seconds(10);
};

/// Throws ClientError unless `reply` is of the kind `expected`: reading the expected field of
/// another kind of reply would silently give an empty message.
void check_reply(const felt::v1::ServerMessage& reply, felt::v1::ServerMessage::BodyCase expected);

/// Microseconds of the client's steady clock: what ProxyUpdate.client_time_us carries.
std::uint64_t steady_microseconds();

}  // namespace felt::client
