#include "net/websocket_transport.hpp"

#include <algorithm>
#include <chrono>

#include <boost/beast/core/buffers_range.hpp>

#include "net/endpoint_text.hpp"

namespace felt::net {

namespace asio = boost::asio;
namespace websocket = boost::beast::websocket;

namespace {

/// Bytes asked of the socket per read.
constexpr std::size_t kReadChunk = 16 * 1024;
/// A closing handshake the client does not answer in this time ends with the socket closed.
constexpr auto kCloseTimeout = std::chrono::seconds(2);

}  // namespace

WebSocketTransport::WebSocketTransport(std::unique_ptr<Stream> stream,
                                       std::size_t max_message_bytes)
    : stream_(std::move(stream)),
      executor_(stream_->get_executor()),
      max_message_bytes_(max_message_bytes) {
  boost::system::error_code ec;
  const auto remote = stream_->next_layer().remote_endpoint(ec);
  peer_ = (ec ? std::string("a closed connection") : endpoint_text(remote)) + " over WebSocket";
  stream_->binary(true);
  // the limit is the session's, checked as the bytes come: Beast's own refuses a message by
  // failing the connection at once, before the client could be told why
  stream_->read_message_max(0);
  stream_->set_option(
      websocket::stream_base::timeout{kCloseTimeout, websocket::stream_base::none(), false});
}

void WebSocketTransport::receive(ReadHandler done) {
  if (message_taken_) {
    message_.clear();
    message_done_ = message_taken_ = false;
  }
  // never more than one byte past the limit: that byte says the message is too large
  const std::size_t start = message_.size();
  const std::size_t chunk = std::min(kReadChunk, max_message_bytes_ + 1 - start);
  message_.resize(start + chunk);
  stream_->async_read_some(asio::buffer(message_.data() + start, chunk),
                           [this, start, done = std::move(done)](
                               const boost::system::error_code& ec, std::size_t bytes) {
                             message_.resize(start + bytes);
                             if (!ec) {
                               // a text message is not a felt.v1 message, whatever it says
                               if (stream_->got_text()) failure_ = wire::DecodeStatus::kBadPrefix;
                               if (message_.size() > max_message_bytes_)
                                 failure_ = wire::DecodeStatus::kTooLarge;
                               message_done_ = stream_->is_message_done();
                             }
                             done(ec, bytes);
                           });
}

wire::DecodeResult WebSocketTransport::next() {
  if (failure_ != wire::DecodeStatus::kNeedMore) return {failure_, {}, 0};
  if (!message_done_ || message_taken_) return {};
  message_taken_ = true;
  return {wire::DecodeStatus::kFrame, std::span(message_), 0};
}

bool WebSocketTransport::send(const std::string& frames, WriteHandler done,
                              boost::system::error_code& ec) {
  ec = {};
  if (frames.empty()) return true;
  write_done_ = std::move(done);
  send_from(frames, 0);
  return false;
}

void WebSocketTransport::send_from(const std::string& frames, std::size_t offset) {
  const std::optional<wire::FrameView> frame =
      wire::first_frame(std::string_view(frames).substr(offset));
  // the session queues whole frames only
  const std::size_t next = offset + frame->size;
  stream_->async_write(asio::buffer(frame->payload),
                       [this, &frames, next](const boost::system::error_code& ec, std::size_t) {
                         if (ec || next == frames.size()) {
                           std::exchange(write_done_, nullptr)(ec);
                           return;
                         }
                         send_from(frames, next);
                       });
}

void WebSocketTransport::close() {
  boost::system::error_code ignored;
  auto& socket = stream_->next_layer();
  socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket.close(ignored);
}

void WebSocketTransport::finish() {
  if (!stream_->is_open()) return close();
  // the handshake holds the stream, not the session: the session may end before it does
  stream_->async_close(websocket::close_code::normal,
                       [stream = stream_](const boost::system::error_code&) {
                         boost::system::error_code ignored;
                         stream->next_layer().close(ignored);
                       });
}

}  // namespace felt::net
