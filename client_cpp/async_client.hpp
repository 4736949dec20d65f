#pragma once
// felt_client's asynchronous side, for loops that must not wait on the network (a 1 kHz haptic
// loop): a thread of its own runs the connection; requests go out from any thread and their
// replies, forces, frames and events come back through handlers on that thread.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <unordered_map>

#include <boost/asio.hpp>

#include "felt/v1/envelope.pb.h"
#include "felt_client.hpp"
#include "wire/frame_codec.hpp"

namespace felt::client {

class AsyncClient {
 public:
  using ReplyHandler = std::function<void(const felt::v1::ServerMessage&)>;
  /// A ForceUpdate and the client's steady clock (µs) when it was read.
  using ForceHandler = std::function<void(const felt::v1::ForceUpdate&, std::uint64_t)>;
  using FrameHandler = std::function<void(const felt::v1::Frame&)>;
  using EventHandler = std::function<void(const felt::v1::SceneEvent&)>;
  using ErrorHandler = std::function<void(const felt::v1::Error&)>;

  AsyncClient();
  ~AsyncClient();
  AsyncClient(const AsyncClient&) = delete;
  AsyncClient& operator=(const AsyncClient&) = delete;

  // Handlers are set before connect() and run on the client's thread; they must not block.
  void on_force(ForceHandler handler) { on_force_ = std::move(handler); }
  void on_frame(FrameHandler handler) { on_frame_ = std::move(handler); }
  void on_event(EventHandler handler) { on_event_ = std::move(handler); }
  /// Errors no reply handler takes: the answers to requests sent without one (a refused
  /// ProxyUpdate), the server's last Error before it closes the connection (request id 0), and
  /// the end of a connection that close() did not end, when the server gave no reason.
  void on_error(ErrorHandler handler) { on_error_ = std::move(handler); }

  /// Connects, starts the client's thread and says Hello; throws ClientError.
  felt::v1::Welcome connect(const std::string& host, std::uint16_t port,
                            const std::string& client_name, const std::string& token = "",
                            std::chrono::milliseconds timeout = std::chrono::seconds(5));
  /// Ends the connection; the requests still waiting get an Error.
  void close();
  /// False once the connection has ended.
  bool connected() const { return connected_; }

  /// Sends `message` under a fresh request id (returned); `on_reply` gets its reply or Error,
  /// also when the connection ends first (at once, on the calling thread, if it has ended).
  /// Safe from any thread; never waits.
  std::uint64_t send(felt::v1::ClientMessage message, ReplyHandler on_reply = {});
  /// Sends a ProxyUpdate stamped with the steady clock; the ForceUpdate goes to on_force.
  void send_proxy_update(std::uint32_t proxy_id, const Point& position, std::uint32_t buttons = 0);
  /// Sends `message` and waits for its reply (for a program's setup); an Error throws.
  felt::v1::ServerMessage request(felt::v1::ClientMessage message,
                                  std::chrono::milliseconds timeout = std::chrono::seconds(10));

 private:
  void read();
  /// Queues `bytes` behind what is waiting, or writes them at once from the calling thread.
  void write(std::string bytes);
  void write_next();
  void deliver(felt::v1::ServerMessage& message);
  /// The connection is over: nothing more is written and every waiting request gets `why`.
  void end(const felt::v1::Error& why);

  boost::asio::io_context io_;
  boost::asio::ip::tcp::socket socket_;
  wire::FrameDecoder decoder_;
  std::array<std::uint8_t, 64 * 1024> buffer_;
  // Writes happen on the caller's thread while nothing waits (no wake of the client's thread
  // on a 1 kHz loop's path), else on the client's thread in order; the mutex keeps them apart.
  std::mutex write_mutex_;
  std::deque<std::string> outbox_;  ///< its front is being written by the client's thread
  bool open_ = false;               ///< the socket may be written to (not closed yet)
  std::atomic<bool> connected_{false};
  std::atomic<std::uint64_t> next_request_id_{1};
  std::mutex handlers_mutex_;
  std::unordered_map<std::uint64_t, ReplyHandler> handlers_;
  felt::v1::Error ended_;  ///< why the connection is over, once it is (under handlers_mutex_)
  // the client's thread only
  bool closing_ = false;                      ///< close() ends the connection
  std::optional<felt::v1::Error> last_word_;  ///< the server's Error with request id 0
  ForceHandler on_force_;
  FrameHandler on_frame_;
  EventHandler on_event_;
  ErrorHandler on_error_;
  std::thread thread_;
};

}  // namespace felt::client
